// The benches' command-line numbers: `--name N`, a positive integer, or the fallback.
// A bad value stops the bench with a clear message (exit 2).
export function positiveIntArg(name, fallback) {
  const i = process.argv.indexOf(name);
  if (i < 0) return fallback;
  const v = Number(process.argv[i + 1]);
  if (!Number.isInteger(v) || v < 1) {
    console.error(`${name} needs a positive integer, got "${process.argv[i + 1]}"`);
    process.exit(2);
  }
  return v;
}
