/**
 * Maxl as the queue's one author: waits for room that an AbortSignal gives up,
 * and edits of the untransmitted tail (replace, cancel one, cancel from), with the
 * queue's own executor (queueOf) standing in for the streamer.
 */
import { describe, expect, it } from 'vitest';
import { createMAXL, MaxlError, type MaxlConfig, type MoveReceipt } from './index.ts';
import { queueOf } from './maxl.ts';
import { blotPlotter } from './sim/presets/index.ts';
import { settle, startMachine } from './system/harness.ts';

const config = (queueCapacity = 2): MaxlConfig => ({ motionAxes: ['x', 'y'], limits: { maxVelocity: 100, maxAcceleration: 1000 }, queueCapacity });

async function rejection(p: Promise<unknown>): Promise<MaxlError> {
  const err = await p.then(
    () => null,
    (e: unknown) => e,
  );
  expect(err).toBeInstanceOf(MaxlError);
  return err as MaxlError;
}

/**
 * A queue of capacity 2 with no room: two moves with a right-angle corner between
 * them, so the first one's plan is final (it ends at the corner's speed whatever
 * follows) and the lookahead does not ask for more path (TrajectoryQueue.hasRoom).
 */
async function fullQueue() {
  const maxl = createMAXL(config(2));
  await maxl.addSegmentToQueue({ endPosition: [10, 0] });
  await maxl.addSegmentToQueue({ endPosition: [10, 10] });
  expect(maxl.queue.hasRoom()).toBe(false);
  return maxl;
}

/** Lets pending promise callbacks run. */
const turn = () => new Promise((resolve) => setTimeout(resolve, 0));

describe('addSegmentToQueue with an AbortSignal', () => {
  it('gives up a wait for room: ABORTED, the move never queued, the next move starting from the path as it stands', async () => {
    const maxl = createMAXL(config());
    await maxl.addSegmentToQueue({ endPosition: [10, 0] });
    await maxl.addSegmentToQueue({ endPosition: [10, 10] });
    expect(maxl.queue.hasRoom()).toBe(false);
    const controller = new AbortController();
    const waiting = maxl.addSegmentToQueue({ endPosition: [50, 50] }, { signal: controller.signal });
    expect(maxl.nextMoveStart).toEqual([50, 50]);
    controller.abort('the job was cancelled');
    const err = await rejection(waiting);
    expect(err.code).toBe('ABORTED');
    expect(err.message).toMatch(/aborted: the job was cancelled/);
    expect(maxl.nextMoveStart).toEqual([10, 10]);
    // Room frees up: nothing of the aborted move arrives.
    queueOf(maxl).transmitNext(0);
    await turn();
    expect(maxl.queue.untransmittedCount).toBe(1);
    expect(maxl.queue.tailPosition).toEqual([10, 10]);
  });

  it('refuses at once with a signal already aborted, queueing nothing even with room', async () => {
    const maxl = createMAXL(config());
    const err = await rejection(maxl.addSegmentToQueue({ endPosition: [10, 0] }, { signal: AbortSignal.abort() }));
    expect(err.code).toBe('ABORTED');
    expect(maxl.queue.size).toBe(0);
  });

  it('an aborted waiter leaves the line: the one behind it gets the next slot, in order', async () => {
    const maxl = await fullQueue();
    const first = new AbortController();
    const a = maxl.addSegmentToQueue({ endPosition: [20, 0] }, { signal: first.signal });
    const b = maxl.addSegmentToQueue({ endPosition: [30, 0] }, { signal: new AbortController().signal });
    first.abort();
    expect((await rejection(a)).code).toBe('ABORTED');
    queueOf(maxl).transmitNext(0);
    const receipt: MoveReceipt = await b;
    expect(maxl.queue.get(receipt.segmentIds[0])?.start).toEqual([10, 10]);
    expect(maxl.queue.get(receipt.segmentIds[0])?.end).toEqual([30, 0]);
    expect(maxl.queue.untransmittedCount).toBe(2);
  });

  it('an abort after the slot came but before the move was appended still gives the move up, and the slot back', async () => {
    const maxl = await fullQueue();
    const controller = new AbortController();
    const a = maxl.addSegmentToQueue({ endPosition: [20, 0] }, { signal: controller.signal });
    queueOf(maxl).transmitNext(0); // grants the slot now; the move is appended a turn later
    controller.abort();
    expect((await rejection(a)).code).toBe('ABORTED');
    expect(maxl.queue.untransmittedCount).toBe(1);
    expect(maxl.queue.hasRoom()).toBe(true);
  });
});

describe('editing the untransmitted tail through Maxl', () => {
  it('replaceMove moves one point of the tail; later moves keep their ends', async () => {
    const maxl = createMAXL(config(16));
    const a = await maxl.addSegmentToQueue({ endPosition: [10, 0] });
    const b = await maxl.addSegmentToQueue({ endPosition: [20, 0] });
    await maxl.addSegmentToQueue({ endPosition: [30, 0] });
    const r = maxl.replaceMove(b.moveId, { endPosition: [20, 5] });
    const ends = maxl.queue.segments().map((s) => [...s.end]);
    expect(ends).toEqual([
      [10, 0],
      [20, 5],
      [30, 0],
    ]);
    expect(r.moveId).not.toBe(b.moveId);
    // The first move is transmitted: locked.
    queueOf(maxl).planToRest();
    queueOf(maxl).transmitNext(0);
    expect(() => maxl.replaceMove(a.moveId, { endPosition: [1, 1] })).toThrow(expect.objectContaining({ code: 'SEGMENT_LOCKED' }));
    expect(() => maxl.cancelMove(a.moveId)).toThrow(expect.objectContaining({ code: 'SEGMENT_LOCKED' }));
  });

  it('replaceMove validates the new move, and a bad one changes nothing', async () => {
    const maxl = createMAXL({ ...config(16), softLimits: { x: [0, 100], y: [0, 100] } });
    const a = await maxl.addSegmentToQueue({ endPosition: [10, 0] });
    expect(() => maxl.replaceMove(a.moveId, { endPosition: [200, 0] })).toThrow(expect.objectContaining({ code: 'SOFT_LIMIT' }));
    expect(maxl.queue.segments().map((s) => [...s.end])).toEqual([[10, 0]]);
  });

  it('cancelMove drops one move; cancelMovesFrom drops it and all after it', async () => {
    const maxl = createMAXL(config(16));
    await maxl.addSegmentToQueue({ endPosition: [10, 0] });
    const b = await maxl.addSegmentToQueue({ endPosition: [20, 0] });
    const c = await maxl.addSegmentToQueue({ endPosition: [30, 0] });
    await maxl.addSegmentToQueue({ endPosition: [40, 0] });
    maxl.cancelMove(c.moveId);
    expect(maxl.queue.segments().map((s) => s.end[0])).toEqual([10, 20, 40]);
    maxl.cancelMovesFrom(b.moveId);
    expect(maxl.queue.segments().map((s) => s.end[0])).toEqual([10]);
    expect(maxl.nextMoveStart).toEqual([10, 0]);
    expect(() => maxl.cancelMove(9999)).toThrow(expect.objectContaining({ code: 'SEGMENT_NOT_FOUND' }));
  });

  it('refuses edits once the instance is closed', async () => {
    const maxl = createMAXL(config(16));
    const a = await maxl.addSegmentToQueue({ endPosition: [10, 0] });
    maxl.close();
    expect(() => maxl.cancelMove(a.moveId)).toThrow(expect.objectContaining({ code: 'QUEUE_CLOSED' }));
  });
});

describe('the read-only views', () => {
  it('maxl.queue and maxl.history follow the queue live, and hold none of its editing or executing methods', async () => {
    const maxl = createMAXL(config(16));
    for (const name of ['append', 'appendValidated', 'replace', 'cancel', 'cancelAll', 'cancelFrom', 'transmitNext', 'splitFront', 'brakeToRest', 'retireUntil', 'planToRest', 'reserveSlot']) {
      expect(name in maxl.queue, name).toBe(false);
    }
    expect('push' in maxl.history).toBe(false);
    await maxl.addSegmentToQueue({ endPosition: [10, 0] });
    expect(maxl.queue.size).toBe(1);
    expect(maxl.queue.tailPosition).toEqual([10, 0]);
    const seen: string[] = [];
    maxl.queue.subscribe((e) => seen.push(e.type));
    queueOf(maxl).planToRest();
    const seg = queueOf(maxl).transmitNext(0)!;
    expect(seen).toContain('transmitted');
    expect(maxl.queue.transmittedEnd_us).toBe(seg.endTime_us);
    expect(maxl.history.size).toBe(1);
    expect(maxl.history.sample(seg.endTime_us)?.position).toEqual([10, 0]);
  });
});

describe('whenIdle with an AbortSignal', () => {
  it('gives up the wait with ABORTED while the machine goes on to finish', async () => {
    const b = await startMachine(blotPlotter());
    for (const x of [30, 60, 30]) await b.maxl.addSegmentToQueue({ endPosition: [x, 40] });
    const controller = new AbortController();
    const given = b.maxl.whenIdle({ signal: controller.signal });
    await b.scheduler.advance(100_000);
    controller.abort();
    expect((await rejection(given)).code).toBe('ABORTED');
    expect(b.maxl.queue.transmittedEnd_us).toBeGreaterThan(b.scheduler.now());
    await settle(b.scheduler, b.maxl.whenIdle(), 10_000_000);
    const [x, y] = b.maxl.sample(b.scheduler.now()).position;
    expect(x).toBeCloseTo(30, 9);
    expect(y).toBeCloseTo(40, 9);
    expect((await rejection(b.maxl.whenIdle({ signal: AbortSignal.abort() }))).code).toBe('ABORTED');
  });
});
