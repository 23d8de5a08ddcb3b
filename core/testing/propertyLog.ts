/**
 * A fast-check reporter that writes down what each property really ran, for
 * `npm run bench -- properties` (bench/properties.ts). fast-check calls it with
 * its run details once a property is done (fc.assert, sync or async); it appends
 * one JSON line to the log and then fails the test exactly as fast-check's own
 * reporter would (the same message), so the test's outcome does not change.
 *
 *   numRuns   the cases fast-check executed (those that passed a precondition,
 *             up to and including a failing one; shrinking is not counted)
 *   numSkips  the cases a precondition (fc.pre) threw away
 */
import { appendFileSync } from 'node:fs';
import fc from 'fast-check';
import { expect } from 'vitest';

export interface PropertyLogLine {
  file: string;
  test: string;
  numRuns: number;
  numSkips: number;
  numShrinks: number;
  failed: boolean;
  interrupted: boolean;
  seed: number;
  /** fast-check's report (counterexample, seed and path to replay it) when it failed */
  report?: string;
}

export function propertyLogReporter(file: string): (details: fc.RunDetails<unknown>) => void {
  return (details) => {
    const state = expect.getState();
    const line: PropertyLogLine = {
      file: state.testPath ?? '?',
      test: state.currentTestName ?? '?',
      numRuns: details.numRuns,
      numSkips: details.numSkips,
      numShrinks: details.numShrinks,
      failed: details.failed,
      interrupted: details.interrupted,
      seed: details.seed,
    };
    const report = details.failed ? fc.defaultReportMessage(details as Parameters<typeof fc.defaultReportMessage>[0]) : undefined;
    if (report !== undefined) line.report = report;
    // One short write per line with O_APPEND: lines from parallel test workers do not interleave.
    appendFileSync(file, `${JSON.stringify(line)}\n`);
    if (report !== undefined) throw new Error(report);
  };
}
