// Vitest setup: property tests are deterministic by default (the same seed on every
// run, so CI cannot flake), and explore further on demand:
//   FC_SEED=123 FC_RUNS=5000 npx vitest run
// With MAXL_PROPERTY_LOG=FILE, every fc.assert also appends one JSON line to FILE
// with what fast-check itself reports it ran (propertyLog.ts); `npm run bench --
// properties` counts the cases from there.
import fc from 'fast-check';
import { propertyLogReporter } from './propertyLog.ts';

const seed = process.env.FC_SEED ? Number(process.env.FC_SEED) : 20261122;
const logFile = process.env.MAXL_PROPERTY_LOG;
fc.configureGlobal({
  seed,
  numRuns: process.env.FC_RUNS ? Number(process.env.FC_RUNS) : 200,
  ...(logFile ? { reporter: propertyLogReporter(logFile) } : {}),
});
