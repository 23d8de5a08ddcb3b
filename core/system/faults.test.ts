/**
 * The fault matrix, seeded subset (the whole matrix: `npm run bench -- faults`).
 * Each case runs a job on a simulated machine (real firmware in wasm, virtual
 * time), injects one fault, waits for the stop, undoes the fault, reconnects and
 * resumes to the job's end (faultCases.ts says what each figure means).
 */
import { describe, expect, it } from 'vitest';
import { seededRandom } from '../random.ts';
import { runFaultCase, type FaultCase, type FaultOutcome } from './faultCases.ts';
import { runLongJob } from './longJob.ts';

/** A board that restarted resumes from the plan at its last frame: off by v × the time since (see faultCases.ts). */
const RESTART_TOLERANCE_MM = 0.5;

function expectSurvived(r: FaultOutcome, mustStop = true): void {
  const restarted = r.case.kind === 'reboot';
  const tolerance = restarted ? RESTART_TOLERANCE_MM : 0.03;
  if (mustStop) expect(r.stops).toBeGreaterThan(0);
  if (r.stops > 0) {
    expect(r.detection_ms).not.toBeNull();
    expect(r.detection_ms!).toBeLessThan(500);
  }
  expect(r.restSteady).toBe(true);
  expect(r.offPathAtRest_mm).toBeLessThanOrEqual(0.03 + r.spread_mm);
  expect(r.offPath_mm).toBeLessThanOrEqual(tolerance + r.spread_mm);
  expect(r.worstBack_mm).toBeLessThanOrEqual(0.03);
  if (!restarted) expect(r.lateSteps).toBeLessThanOrEqual(0);
  expect(r.stateOk).toBe(true);
  expect(r.resumed).toBe(true);
  expect(r.endError_mm).toBeLessThanOrEqual(restarted ? RESTART_TOLERANCE_MM : 0.02);
}

const random = seededRandom(1111);
const moment = () => 0.1 + 0.8 * random();

describe('a link cut at a random moment, then reconnect and resume', () => {
  const cases: FaultCase[] = [
    { preset: 'blotPlotter', kind: 'cut', seed: 31, at: moment() },
    { preset: 'lightPainter', kind: 'cut', seed: 32, at: moment(), device: 'lightPainter' },
    { preset: 'lightPainter', kind: 'cut', seed: 33, at: moment(), device: 'motorA' },
    { preset: 'accelRig', kind: 'cut', seed: 34, at: moment(), device: 'motorOne' },
    { preset: 'accelRig', kind: 'cut', seed: 35, at: moment(), device: 'accelerometer' },
  ];
  it.each(cases.map((c) => [c.preset, c.device ?? 'blot', Math.round(c.at * 100), c] as const))('%s, %s cut %i %% into the job', async (_p, _d, _at, c) => {
    expectSurvived(await runFaultCase(c));
  }, 120_000);
});

describe('other faults, then reconnect and resume', () => {
  it.each([
    ['a device restart mid-job', { preset: 'blotPlotter', kind: 'reboot', seed: 41, at: 0.45 }],
    ['a device clock jump (+50 ms)', { preset: 'blotPlotter', kind: 'clockJump', seed: 42, at: 0.55 }],
    ['a clock jump (+50 ms) on one board of several: the others stop with it on the path', { preset: 'lightPainter', kind: 'clockJump', seed: 47, at: 0.45, device: 'motorA' }],
    ['a device clock running back (−20 ms)', { preset: 'lightPainter', kind: 'clockJump', seed: 48, at: 0.55, device: 'motorB', jump_us: -20_000 }],
    ['a 200 ms latency spike', { preset: 'blotPlotter', kind: 'latency', seed: 43, at: 0.35 }],
    ['a cut just after the board’s u32 µs counter wrapped', { preset: 'blotPlotter', kind: 'wrap', seed: 44, at: 0.3 }],
    ['byte corruption 1e-2 on every link', { preset: 'blotPlotter', kind: 'corrupt', seed: 45, at: 0, corruption: 1e-2 }],
  ] as Array<[string, FaultCase]>)('%s', async (_what, c) => {
    expectSurvived(await runFaultCase(c), c.kind !== 'corrupt');
  }, 120_000);

  it('byte corruption 1e-3: the same executed trajectory as a clean run', async () => {
    const clean = await runFaultCase({ preset: 'lightPainter', kind: 'corrupt', seed: 46, at: 0, corruption: 0 });
    const noisy = await runFaultCase({ preset: 'lightPainter', kind: 'corrupt', seed: 46, at: 0, corruption: 1e-3 });
    expect(noisy.resends).toBeGreaterThan(0);
    expect(noisy.stops).toBe(0);
    expectSurvived(noisy, false);
    expect(noisy.plan.length).toBe(clean.plan.length);
    clean.plan.forEach((p, k) => p.forEach((v, i) => expect(noisy.plan[k][i]).toBeCloseTo(v, 6)));
  }, 120_000);
});

describe('a cut in the job\'s last moments', () => {
  it('the job runs to its end on the boards; the loss is still detected and said, with nothing left to resume', async () => {
    // 96 % in: the job ends ~100 ms later, the 300 ms silence limit after that.
    const r = await runFaultCase({ preset: 'accelRig', kind: 'cut', seed: 36, at: 0.96, device: 'accelerometer' });
    expect(r.endedBeforeStop).toBe(true);
    expect(r.reasons).toEqual(['lost']);
    expectSurvived(r); // detected < 500 ms after the cut, words "had already run to its end", reconnect() finds nothing left
  }, 120_000);
});

describe('a long job', () => {
  it('one hour (eight in the bench), a stroke every 5 minutes on a 150 ppm crystal across the u32 wrap: drift stays bounded', async () => {
    const r = await runLongJob(3.6e9, 300_000_000);
    expect(r.strokes).toBe(12);
    expect(r.wraps).toBe(1);
    expect(r.worstLateSteps).toBeLessThanOrEqual(0); // every stroke on its plan within a step (+ the model's error)
    expect(r.lastStrokeSteps).toBeLessThan(2);
    expect(r.settledModelError_us).toBeLessThan(100);
    expect(r.errors).toEqual([]);
  }, 300_000);
});
