/**
 * `npm run bench -- properties [--runs N] [--seed S]`: every fast-check property
 * of the project (each core/** and app/** test file that calls fc.assert, found
 * afresh on every run) at a scale the test suite cannot afford: N cases per
 * property (default 6 000, where `npm test` runs 200), at least 100 000 in all.
 *
 * The count is not assumed from N: the vitest setup (core/testing/setup.ts) sets
 * fast-check's global numRuns from FC_RUNS and, with MAXL_PROPERTY_LOG, a reporter
 * (core/testing/propertyLog.ts) that appends fast-check's own run details of every
 * fc.assert to a log. A property that fixes its own numRuns runs that many; the
 * log says so and the sum counts it as it ran.
 *
 * Prints one JSON object as the last line:
 *   cases              sum of fast-check's numRuns over every property run: the
 *                      generated inputs actually executed (fc.pre rejections and
 *                      shrinking steps not counted)
 *   properties         fc.assert calls that reported
 *   failures           properties that failed: file, test, and fast-check's report
 *                      (counterexample, seed and path to replay it)
 *   failedTests        vitest tests that failed for any reason (a property's
 *                      failure, or an error outside one)
 *   fixedRuns          properties that ran fewer than runsPerProperty because the
 *                      test fixes numRuns, with the count they ran
 *   skips              cases thrown away by fc.pre
 *   runsPerProperty, seed, files, seconds (wall time of the vitest run)
 * Exits non-zero on a failure or when fewer than 100 000 cases ran.
 */
import { spawn } from 'node:child_process';
import { existsSync, mkdtempSync, readdirSync, readFileSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import type { PropertyLogLine } from '../core/testing/propertyLog.ts';
import { positiveIntArg } from './args.mjs';

const MINIMUM_CASES = 100_000;
const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const runsPerProperty = positiveIntArg('--runs', 6000);
const seed = positiveIntArg('--seed', 20261122);
const log = (...a: unknown[]) => console.error('[bench properties]', ...a);

/** Every *.test.ts under core/ and app/ that holds a property. */
function propertyFiles(dir: string): string[] {
  const found: string[] = [];
  for (const entry of readdirSync(dir)) {
    const full = path.join(dir, entry);
    if (entry === 'node_modules') continue;
    if (statSync(full).isDirectory()) found.push(...propertyFiles(full));
    else if (entry.endsWith('.test.ts') && readFileSync(full, 'utf8').includes('fc.assert')) found.push(path.relative(root, full));
  }
  return found;
}
const files = [...propertyFiles(path.join(root, 'core')), ...propertyFiles(path.join(root, 'app'))].sort();

const work = mkdtempSync(path.join(tmpdir(), 'maxl-properties-'));
const propertyLog = path.join(work, 'properties.jsonl');
const vitestJson = path.join(work, 'vitest.json');
const readLog = (): PropertyLogLine[] =>
  existsSync(propertyLog)
    ? readFileSync(propertyLog, 'utf8')
        .split('\n')
        .filter(Boolean)
        .map((l) => JSON.parse(l) as PropertyLogLine)
    : [];

log(`${files.length} files with properties, ${runsPerProperty} cases per property, seed ${seed}`);
const started = Date.now();
const progress = setInterval(() => {
  const lines = readLog();
  log(`${lines.length} properties done, ${lines.reduce((s, l) => s + l.numRuns, 0).toLocaleString('en')} cases, ${Math.round((Date.now() - started) / 1000)} s`);
}, 20_000);
const status = await new Promise<number>((resolve, reject) => {
  const p = spawn('npx', ['vitest', 'run', ...files, '--testTimeout=1200000', '--reporter=json', `--outputFile=${vitestJson}`], {
    cwd: root,
    stdio: ['ignore', 'ignore', 'inherit'],
    env: { ...process.env, FC_RUNS: String(runsPerProperty), FC_SEED: String(seed), MAXL_PROPERTY_LOG: propertyLog },
  });
  p.on('error', reject);
  p.on('close', (code) => resolve(code ?? 1));
});
clearInterval(progress);
const seconds = Math.round((Date.now() - started) / 1000);

const lines = readLog();
interface VitestJson {
  testResults: Array<{ name: string; message?: string; assertionResults: Array<{ fullName: string; status: string; failureMessages: string[] }> }>;
}
const vitest: VitestJson | null = existsSync(vitestJson) ? (JSON.parse(readFileSync(vitestJson, 'utf8')) as VitestJson) : null;
const failedTests = vitest
  ? vitest.testResults.flatMap((f) => [
      ...(f.assertionResults.length === 0 && f.message ? [{ file: path.relative(root, f.name), test: '(file)', message: f.message.slice(0, 2000) }] : []),
      ...f.assertionResults
        .filter((a) => a.status === 'failed')
        .map((a) => ({ file: path.relative(root, f.name), test: a.fullName, message: a.failureMessages.join('\n').slice(0, 2000) })),
    ])
  : [{ file: '(vitest)', test: '(run)', message: `vitest exited ${status} without its JSON report` }];
const cases = lines.reduce((s, l) => s + l.numRuns, 0);
const summary = {
  cases,
  properties: lines.length,
  failures: lines.filter((l) => l.failed).map((l) => ({ file: path.relative(root, l.file), test: l.test, report: l.report })),
  failedTests: failedTests.length,
  failedTestList: failedTests,
  fixedRuns: lines.filter((l) => !l.failed && l.numRuns + l.numSkips < runsPerProperty).map((l) => ({ test: l.test, numRuns: l.numRuns })),
  skips: lines.reduce((s, l) => s + l.numSkips, 0),
  runsPerProperty,
  seed,
  files: files.length,
  seconds,
  minimumCases: MINIMUM_CASES,
};
console.log(JSON.stringify(summary));
process.exit(summary.failures.length > 0 || failedTests.length > 0 || status !== 0 || cases < MINIMUM_CASES ? 1 : 0);
