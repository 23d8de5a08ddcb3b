// The suites `npm test` runs, in order, and the system tools each needs.
export const suites = [
  {
    name: 'typecheck',
    describe: 'TypeScript (strict) and Svelte type checks',
    command: ['npx', 'svelte-check', '--tsconfig', './tsconfig.json', '--threshold', 'error'],
  },
  {
    name: 'unit',
    describe: 'vitest: core planner, queue, tracks, transforms (property tests included)',
    command: ['npx', 'vitest', 'run'],
  },
];
