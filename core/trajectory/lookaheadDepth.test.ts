/**
 * The queue's lookahead is as deep as braking needs (queue.ts hasRoom, plan/lookahead.ts):
 * at the default capacity, a producer loop drained by a DryRun plans a finely
 * flattened curve exactly as planPath plans the whole path, through the planner's
 * store growing and wrapping, and through edits of the deep unsent tail.
 */
import { describe, expect, it } from 'vitest';
import { createMAXL, planPath, type MaxlConfig } from '../index.ts';
import { DEFAULT_QUEUE_CAPACITY } from '../config/validate.ts';
import { queueOf } from '../maxl.ts';
import { DryRun } from './dryRun.ts';
import { MAX_LOOKAHEAD_SEGMENTS } from './queue.ts';
import type { Segment } from './segment.ts';

const LIMITS = { maxVelocity: 250, maxAcceleration: 3000, junctionDeviation: 0.05 };
const config: MaxlConfig = { motionAxes: ['x', 'y'], limits: LIMITS };
/** mm: braking from 250 mm/s at 3 000 mm/s², v²/2a. */
const BRAKING_MM = (250 * 250) / (2 * 3000);

/** One turn of a circle in `count` chords of `step` mm, from (r, 0). */
function circle(count: number, step: number): { start: number[]; points: number[][] } {
  const r = (count * step) / (2 * Math.PI);
  const points = Array.from({ length: count }, (_, k) => [r * Math.cos((2 * Math.PI * (k + 1)) / count), r * Math.sin((2 * Math.PI * (k + 1)) / count)]);
  return { start: [r, 0], points };
}

/** Plans `points` through the queue at default settings, a producer loop drained by a DryRun; returns what was run. */
async function runIncrementally(start: number[], points: number[][], onAdded?: (k: number, maxl: ReturnType<typeof createMAXL>) => void) {
  const maxl = createMAXL(config, { initialPosition: start });
  const taken: Segment[] = [];
  let deepest = 0;
  const dry = new DryRun(queueOf(maxl), (seg) => taken.push(seg));
  for (let k = 0; k < points.length; k++) {
    await maxl.addSegmentToQueue({ endPosition: points[k] });
    onAdded?.(k, maxl);
    deepest = Math.max(deepest, queueOf(maxl).untransmittedCount);
    dry.takeWhileFull();
  }
  dry.finish();
  return { taken, deepest, dry, maxl };
}

describe('lookahead as deep as braking needs', () => {
  it('plans 3 µm chords as planPath does, holding more than the capacity while the front is not final', async () => {
    // 8 000 chords of 3 µm: 24 mm of path, r ≈ 3.8 mm; 512 chords hold only 1.5 mm of it.
    const { start, points } = circle(8000, 0.003);
    const { taken, deepest, dry } = await runIncrementally(start, points);
    const batch = planPath(start, points.map((end) => ({ end })), LIMITS);
    expect(taken.length).toBe(batch.segmentCount);
    expect(dry.segments).toBe(taken.length);
    // The whole plan: within 1e-6 of planPath's, where a 512-deep lookahead loses half the speed.
    expect(dry.duration_s / batch.duration).toBeLessThanOrEqual(1.000001);
    expect(dry.duration_s / batch.duration).toBeGreaterThanOrEqual(0.999999);
    // Segment by segment too.
    taken.forEach((seg, i) => expect(seg.duration_s).toBeCloseTo(batch.segments[i].duration, 9));
    // It held at least a braking distance of chords (the store grew past its first 1 024 slots).
    expect(deepest).toBeGreaterThan(DEFAULT_QUEUE_CAPACITY);
    expect(deepest * 0.003).toBeGreaterThanOrEqual(BRAKING_MM);
    expect(deepest * 0.003).toBeLessThan(BRAKING_MM + 1);
  });

  it('takes no more than the capacity when the front is final within it', async () => {
    // 5 mm sides: a braking distance is two of them, far fewer than 512.
    const points = Array.from({ length: 2000 }, (_, k) => [5 * (k + 1), (k % 2) * 5]);
    const { deepest, dry } = await runIncrementally([0, 0], points);
    expect(deepest).toBe(DEFAULT_QUEUE_CAPACITY);
    expect(dry.duration_s).toBeCloseTo(planPath([0, 0], points.map((end) => ({ end })), LIMITS).duration, 9);
  });

  it('stays optimal through a replan of the deep unsent tail', async () => {
    const { start, points } = circle(6000, 0.003);
    // Once 4 000 chords are in, replace the move 1 500 back (deep in the tail, in a store
    // that has grown and wrapped) by the same line: the queue replans every untransmitted
    // segment from its front, and the plan must come out as planPath's still. (A replace
    // that changed the path would make the plan of segments locked before it no longer
    // optimal for the new path, only safe.)
    let replaced = 0;
    const { taken } = await runIncrementally(start, points, (k, maxl) => {
      if (k !== 3999) return;
      const q = queueOf(maxl);
      expect(q.untransmittedCount).toBeGreaterThan(1500);
      const seg = q.untransmittedAt(q.untransmittedCount - 1500)!;
      q.replace(seg.moveId, { endPosition: [...seg.end] });
      replaced++;
    });
    expect(replaced).toBe(1);
    const batch = planPath(start, points.map((end) => ({ end })), LIMITS);
    expect(taken.length).toBe(batch.segmentCount);
    expect(taken.reduce((t, s) => t + s.duration_s, 0) / batch.duration).toBeCloseTo(1, 6);
    taken.forEach((seg, i) => expect(seg.duration_s).toBeCloseTo(batch.segments[i].duration, 9));
  });

  it('lets waiting producers in one after another while the front needs more path, with no transmit between', async () => {
    const maxl = createMAXL({ ...config, queueCapacity: 1 });
    const q = queueOf(maxl);
    await maxl.addSegmentToQueue({ endPosition: [100, 0] });
    // The front, from rest, is the only segment: it needs more path, so this one comes in too.
    await maxl.addSegmentToQueue({ endPosition: [200, 0] });
    // Now the first is final (100 mm is room enough to brake): the next calls wait, in order.
    expect(q.hasRoom()).toBe(false);
    const ends = [1e-4, 2e-4, 3e-4].map((d) => [200 + d, 0]);
    const added: number[] = [];
    const calls = ends.map((end, i) => maxl.addSegmentToQueue({ endPosition: end }).then(() => added.push(i)));
    await new Promise((r) => setImmediate(r));
    expect(added).toEqual([]);
    // One transmit: the second line is the front, and 0.1 mm after it is no room to brake.
    q.transmitNext(0);
    for (let turn = 0; turn < 5; turn++) await new Promise((r) => setImmediate(r));
    expect(added).toEqual([0, 1, 2]);
    await Promise.all(calls);
    expect(q.untransmittedCount).toBe(4);
  });

  it(`bounds the lookahead at ${MAX_LOOKAHEAD_SEGMENTS} segments on an absurdly fine path`, () => {
    const maxl = createMAXL(config);
    const q = queueOf(maxl);
    // A 100 mm line the machine may leave at full speed, then 1e-7 mm segments straight on:
    // braking from there needs 1e8 of them, so the line's exit is never final.
    q.append({ endPosition: [100, 0] });
    let n = 0;
    while (q.hasRoom()) q.append({ endPosition: [100 + ++n * 1e-7, 0] });
    expect(q.untransmittedCount).toBe(MAX_LOOKAHEAD_SEGMENTS);
    const dry = new DryRun(q);
    dry.takeWhileFull();
    expect(q.untransmittedCount).toBe(MAX_LOOKAHEAD_SEGMENTS - 1);
    dry.finish();
    expect(q.untransmittedCount).toBe(0);
    expect(dry.segments).toBe(MAX_LOOKAHEAD_SEGMENTS);
    // The line was locked before its exit was final: it leaves it slow enough to stop in what followed.
    expect(dry.duration_s).toBeGreaterThan(planPath([0, 0], [{ end: [100 + n * 1e-7, 0] }], LIMITS).duration);
  });
});
