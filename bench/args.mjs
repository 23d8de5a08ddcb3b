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

// A list of seeds from an environment variable: "1-20", "1,4,9" or "3-5,9"; `fallback`
// when the variable is unset. A bad list stops the bench with a clear message (exit 2).
export function seedListEnv(name, fallback) {
  const spec = process.env[name];
  if (spec === undefined || spec === '') return fallback;
  const seeds = [];
  for (const part of spec.split(',')) {
    const m = /^\s*(\d+)\s*(?:-\s*(\d+)\s*)?$/.exec(part);
    const [from, to] = m ? [Number(m[1]), Number(m[2] ?? m[1])] : [NaN, NaN];
    if (!m || to < from) {
      console.error(`${name}: "${part}" is not a seed or a rising range like 1-20 (in "${spec}")`);
      process.exit(2);
    }
    for (let s = from; s <= to; s++) seeds.push(s);
  }
  return seeds;
}
