/**
 * The job runner on a simulated Blot (real firmware in wasm, virtual time): it
 * awaits addSegmentToQueue and whenIdle with the run's AbortSignal instead of
 * polling, so a job is done exactly when the machine finished it, a cancel drops
 * the move waiting for room, and a pause is not mistaken for the end.
 */
import { describe, expect, it } from 'vitest';
import { createMAXL, type Move } from '../../core/index.ts';
import { blotPlotter } from '../../core/sim/presets/index.ts';
import { startMachine, type Bench } from '../../core/system/harness.ts';
import { JobRunner, type MoveJob } from './jobRunner.ts';
import type { JobPhase } from './protocol.ts';

/** n moves of 1 mm, back and forth along a row in the middle of the bed: more than the queue holds. */
function zigzag(n: number): Move[] {
  return Array.from({ length: n }, (_, i) => ({ endPosition: [40 + (i % 2), 40 + Math.floor(i / 2) * 0.01], maxVelocity: 60 }));
}

async function setup(moves: number, job?: Partial<MoveJob>) {
  const b = await startMachine(blotPlotter());
  const logs: string[] = [];
  const runner = new JobRunner({ log: (_level, code, message) => logs.push(`${code} ${message}`), preview: () => {} });
  // As the workbench's snapshot builder does: finished segments count as progress.
  b.maxl.queue.subscribe((e) => {
    if (e.type === 'historical') for (const s of e.segments) runner.onHistorical(s);
  });
  expect(runner.startMoves({ name: 'zigzag', moves: zigzag(moves), ...job }, b.maxl)).toBe(true);
  const phase = () => runner.progress()?.phase as JobPhase;
  return { b, runner, logs, phase };
}

/** Runs virtual time while `busy`, at most `limit_us`. */
async function runWhile(b: Bench, busy: () => boolean, limit_us = 60_000_000): Promise<void> {
  await b.scheduler.runWhile(busy, b.scheduler.now() + limit_us);
}

describe('JobRunner', () => {
  it('is done when the machine has run every move, not before', async () => {
    const { b, runner, logs, phase } = await setup(700);
    let doneWhileMoving = false;
    await runWhile(b, () => {
      if (phase() === 'done' && b.maxl.queue.transmittedEnd_us > b.scheduler.now()) doneWhileMoving = true;
      return phase() === 'running';
    });
    expect(phase()).toBe('done');
    expect(doneWhileMoving).toBe(false);
    expect(runner.fed).toBe(700);
    expect(b.maxl.queue.untransmittedCount).toBe(0);
    expect(b.maxl.queue.transmittedEnd_us).toBeLessThanOrEqual(b.scheduler.now());
    expect(runner.progress()?.doneSegments).toBe(700);
    expect(logs.at(-1)).toMatch(/^JOB “zigzag” done: 700 segments/);
  });

  it('a cancel while the feed waits for room queues none of the job’s later moves', async () => {
    const { b, runner, phase } = await setup(3000);
    // The queue (512) fills long before 3 000 moves are fed: the feed then waits for room.
    await runWhile(b, () => b.maxl.queue.hasRoom() || runner.fed < 512);
    expect(runner.fed).toBeLessThan(3000);
    const lastQueuedMove = Math.max(...b.maxl.queue.segments().map((s) => s.moveId));
    const addedAfter: number[] = [];
    b.maxl.queue.subscribe((e) => {
      if (e.type === 'added') for (const s of e.segments) addedAfter.push(s.moveId);
    });
    const fedAtCancel = runner.fed;
    runner.cancel();
    await runWhile(b, () => phase() === 'cancelling');
    expect(phase()).toBe('cancelled');
    // Only pieces of moves queued before the cancel (the stop splits one) were added since.
    expect(addedAfter.every((id) => id <= lastQueuedMove)).toBe(true);
    expect(runner.fed).toBe(fedAtCancel);
    // Time goes on: nothing more comes.
    await b.scheduler.advance(500_000);
    expect(runner.fed).toBe(fedAtCancel);
    expect(b.maxl.queue.untransmittedCount).toBe(0);
  });

  it('a paused job is not done while it holds at rest, and finishes after resume', async () => {
    const { b, runner, phase } = await setup(700);
    await b.scheduler.advance(300_000);
    runner.pause();
    await runWhile(b, () => phase() === 'pausing');
    expect(phase()).toBe('paused');
    await b.scheduler.advance(1_000_000);
    expect(phase()).toBe('paused');
    expect(b.maxl.queue.untransmittedCount).toBeGreaterThan(0);
    runner.resume();
    await runWhile(b, () => phase() === 'running');
    expect(phase()).toBe('done');
    expect(runner.progress()?.doneSegments).toBe(700);
  });

  it('a points job with a coordinate that is not a number is refused whole, before anything is queued', () => {
    const maxl = createMAXL(blotPlotter().config, { initialPosition: [10, 10] });
    const logs: string[] = [];
    const runner = new JobRunner({ log: (_level, code, message) => logs.push(`${code} ${message}`), preview: () => {} });
    runner.start({ name: 'points.csv', maxVelocity: 50, points: Float64Array.from([20, 20, 30, 30, 40, NaN, 50, 50]), axes: 2 }, maxl, [0, 0]);
    expect(logs).toEqual(['JOB_INVALID “points.csv”: point 3 has a coordinate that is not a finite number (NaN); nothing was started.']);
    expect(runner.progress()).toBeNull();
    expect(maxl.queue.size).toBe(0);
  });

  // A bad move in a run (found by addSegmentsNow, index 40) and one past the queue's
  // capacity (found after waits for room, index 900): either way the job stops there,
  // every move before it queued and run, and the log names the job's own move and
  // where the tool says it comes from (here a made-up file line: move i is line 2i + 5).
  it.each([40, 900])('a bad move (index %i) stops the job with the job’s own words for it', async (bad) => {
    const moves = zigzag(1200);
    moves[bad] = { ...moves[bad], maxVelocity: 1e-4 };
    const { b, runner, logs, phase } = await setup(0, { name: 'zigzag.gcode', moves, describeMove: (i) => `line ${2 * i + 5} of zigzag.gcode` });
    await runWhile(b, () => phase() === 'running');
    expect(phase()).toBe('failed');
    expect(runner.fed).toBe(bad);
    expect(logs.at(-1)).toBe(
      `MOVE_INVALID “zigzag.gcode” stopped: line ${2 * bad + 5} of zigzag.gcode (move ${bad + 1} of the job): maxVelocity: must be at least 0.001 mm/s, got 0.0001`,
    );
    // Every move before it runs, and nothing of it or after it (progress counts moves by id from the job's first).
    await runWhile(b, () => b.maxl.queue.transmittedEnd_us > b.scheduler.now() || b.maxl.queue.untransmittedCount > 0);
    expect(runner.progress()?.doneSegments).toBe(bad);
    expect(b.maxl.queue.untransmittedCount).toBe(0);
  });
});
