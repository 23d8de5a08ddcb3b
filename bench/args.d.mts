/** `--name N` from the command line, a positive integer, or `fallback` when absent (exit 2 on a bad value). */
export function positiveIntArg(name: string, fallback: number): number;
