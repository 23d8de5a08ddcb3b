// Vitest setup: property tests are deterministic by default (the same seed on every
// run, so CI cannot flake), and explore further on demand:
//   FC_SEED=123 FC_RUNS=5000 npx vitest run
import fc from 'fast-check';

const seed = process.env.FC_SEED ? Number(process.env.FC_SEED) : 20261122;
fc.configureGlobal({ seed, numRuns: process.env.FC_RUNS ? Number(process.env.FC_RUNS) : 200 });
