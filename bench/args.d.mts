/** `--name N` from the command line, a positive integer, or `fallback` when absent (exit 2 on a bad value). */
export function positiveIntArg(name: string, fallback: number): number;
/** Seeds from environment variable `name` ("1-20", "1,4,9", "3-5,9"), or `fallback` when unset (exit 2 on a bad list). */
export function seedListEnv(name: string, fallback: number[]): number[];
