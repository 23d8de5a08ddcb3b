import { describe, expect, it } from 'vitest';
import fc from 'fast-check';
import { createMAXL, MaxlError, phasesOf, type MaxlConfig } from '../index.ts';
import type { QueueEvent } from './queue.ts';
import { refBlocks, refJunctionSpeeds2 } from '../testing/referencePlanner.ts';
import { resolveLimits } from '../config/limits.ts';
import { queueOf } from '../maxl.ts';

const LIMITS = { maxVelocity: 250, maxAcceleration: 3000, junctionDeviation: 0.05 };
const config = (extra: Partial<MaxlConfig> = {}): MaxlConfig => ({ motionAxes: ['x', 'y'], limits: LIMITS, ...extra });

/** A square path, corner to corner. */
const square = [
  [100, 0],
  [100, 100],
  [0, 100],
  [0, 0],
];

function expectCode(fn: () => unknown, code: string, field?: string) {
  try {
    fn();
  } catch (err) {
    expect(err).toBeInstanceOf(MaxlError);
    expect((err as MaxlError).code).toBe(code);
    if (field !== undefined) expect((err as MaxlError).field).toBe(field);
    return err as MaxlError;
  }
  throw new Error(`expected a MaxlError ${code}`);
}

describe('queue states', () => {
  it('moves segments through unplanned → planned → transmitted → historical', () => {
    const maxl = createMAXL(config());
    const q = queueOf(maxl);
    for (const p of square) q.append({ endPosition: p });
    // The first three corners are capped by junction speed (final); the last ends at rest and
    // could still speed up if more path came, so it stays unplanned.
    expect(q.segments().map((s) => s.state)).toEqual(['planned', 'planned', 'planned', 'unplanned']);
    q.planToRest();
    expect(q.segments().every((s) => s.state === 'planned')).toBe(true);

    const first = q.transmitNext(1_000)!;
    expect(first.state).toBe('transmitted');
    expect(first.startTime_us).toBe(1_000);
    const second = q.transmitNext(5_000)!;
    // The machine is still moving at the end of the first: the second follows it exactly.
    expect(second.startTime_us).toBe(first.endTime_us);
    expect(q.retireUntil(first.endTime_us)).toEqual([first]);
    expect(first.state).toBe('historical');
    expect(q.segments()[0]).toBe(second);
  });

  it('starts a segment after rest no earlier than asked, and after the transmitted path', () => {
    const maxl = createMAXL(config());
    const q = queueOf(maxl);
    q.append({ endPosition: [10, 0] });
    const a = q.transmitNext(0)!;
    expect(a.exit2).toBe(0); // the path ended at rest when it was locked
    q.append({ endPosition: [20, 0] });
    const b = q.transmitNext(0)!;
    expect(b.startTime_us).toBe(a.endTime_us); // not before the machine got there
    q.append({ endPosition: [30, 0] });
    const c = q.transmitNext(b.endTime_us + 50_000)!;
    expect(c.startTime_us).toBe(b.endTime_us + 50_000);
  });

  it('keeps an edit from touching transmitted segments, and says why', () => {
    const maxl = createMAXL(config());
    const q = queueOf(maxl);
    const r1 = q.append({ endPosition: [10, 0] });
    const r2 = q.append({ endPosition: [10, 10] });
    q.transmitNext(0);
    const err = expectCode(() => q.cancel(r1.moveId), 'SEGMENT_LOCKED');
    expect(err.message).toMatch(/transmitted/);
    expectCode(() => q.replace(r1.moveId, { endPosition: [5, 5] }), 'SEGMENT_LOCKED');
    expectCode(() => q.cancel(9999), 'SEGMENT_NOT_FOUND');
    // The untransmitted move can still be changed.
    q.replace(r2.moveId, { endPosition: [10, -10] });
    expect(q.segments()[1].end).toEqual([10, -10]);
  });

  it('replans from an edit: later moves start where the path now goes', () => {
    const maxl = createMAXL(config());
    const q = queueOf(maxl);
    const events: QueueEvent[] = [];
    q.subscribe((e) => events.push(e));
    const a = q.append({ endPosition: [10, 0] });
    const b = q.append({ endPosition: [10, 10] });
    const c = q.append({ endPosition: [0, 10] });
    q.cancel(b.moveId);
    const segs = q.segments();
    expect(segs.map((s) => s.moveId)).toEqual([a.moveId, c.moveId]);
    expect(segs[1].start).toEqual([10, 0]); // c now starts where a ended
    expect(segs[1].end).toEqual([0, 10]);
    expect(events.some((e) => e.type === 'removed')).toBe(true);
    // Replace keeps later moves' targets.
    q.replace(a.moveId, { endPosition: [0, 0.5] });
    expect(q.segments().map((s) => s.end)).toEqual([
      [0, 0.5],
      [0, 10],
    ]);
    expect(q.tailPosition).toEqual([0, 10]);
  });

  it('refuses an edit that leaves the moving machine no room to brake, and keeps the queue as it was', () => {
    const maxl = createMAXL(config());
    const q = queueOf(maxl);
    q.append({ endPosition: [100, 0] });
    const b = q.append({ endPosition: [200, 0] });
    q.transmitNext(0); // locked, leaving the first move at speed into the second
    const before = q.segments().map((s) => [s.id, s.start, s.end]);
    const err = expectCode(() => q.cancel(b.moveId), 'CANNOT_STOP_IN_PATH');
    expect(err.message).toMatch(/brake/);
    expect(q.segments().map((s) => [s.id, s.start, s.end])).toEqual(before);
    // A replacement that turns sharply at the locked speed is refused as well.
    expectCode(() => q.replace(b.moveId, { endPosition: [100, 100] }), 'CANNOT_STOP_IN_PATH');
    // One that keeps going straight is fine.
    q.replace(b.moveId, { endPosition: [300, 0] });
    expect(q.segments()[1].end).toEqual([300, 0]);
  });

  it('reports every transition to observers, in order', () => {
    const maxl = createMAXL(config());
    const q = queueOf(maxl);
    const seen: string[] = [];
    q.subscribe((e) => seen.push(`${e.type}:${e.segments.map((s) => s.id).join(',')}`));
    q.append({ endPosition: [10, 0] });
    q.append({ endPosition: [10, 10] });
    q.transmitNext(0);
    q.planToRest();
    const s = q.transmitNext(0)!;
    q.retireUntil(s.endTime_us);
    expect(seen).toEqual(['added:1', 'added:2', 'planned:1', 'transmitted:1', 'planned:2', 'transmitted:2', 'historical:1,2']);
  });
});

describe('bounded queue', () => {
  it('paces a Listing 2 loop: addSegmentToQueue resolves only when there is room', async () => {
    const maxl = createMAXL(config({ queueCapacity: 3 }));
    const path = Array.from({ length: 10 }, (_, i) => [10 * (i + 1), (i % 2) * 10]);
    let added = 0;
    const loop = (async () => {
      for (const p of path) {
        await maxl.addSegmentToQueue({ endPosition: p, maxVelocity: 250 });
        added++;
      }
    })();
    await Promise.resolve();
    await new Promise((r) => setImmediate(r));
    expect(added).toBe(3);
    expect(maxl.queue.untransmittedCount).toBe(3);
    const transmitted: number[] = [];
    while (transmitted.length < 10) {
      const seg = queueOf(maxl).transmitNext(0);
      if (seg) transmitted.push(seg.id);
      await new Promise((r) => setImmediate(r));
      expect(maxl.queue.untransmittedCount).toBeLessThanOrEqual(3);
    }
    await loop;
    expect(added).toBe(10);
    expect(transmitted).toEqual([1, 2, 3, 4, 5, 6, 7, 8, 9, 10]);
    expect(queueOf(maxl).segments().map((s) => s.end)).toEqual(path);
  });

  it('keeps the order of calls that are not awaited, and validates each at once', async () => {
    const maxl = createMAXL(config({ queueCapacity: 1 }));
    const a = maxl.addSegmentToQueue({ endPosition: [10, 0] });
    const b = maxl.addSegmentToQueue({ endPosition: [10, 10] });
    const c = maxl.addSegmentToQueue({ endPosition: { y: 20 } }); // x stays at 10
    await expect(maxl.addSegmentToQueue({ endPosition: [NaN, 0] })).rejects.toMatchObject({ code: 'MOVE_INVALID' });
    await a;
    queueOf(maxl).transmitNext(0);
    await b;
    queueOf(maxl).transmitNext(0);
    await c;
    expect(queueOf(maxl).segments().map((s) => s.end)).toEqual([
      [10, 0],
      [10, 10],
      [10, 20],
    ]);
  });
});

describe('bad input', () => {
  it('rejects NaN, infinities and wrong dimensions with typed errors, enqueuing nothing', () => {
    const maxl = createMAXL(config());
    const q = queueOf(maxl);
    q.append({ endPosition: [1, 1] });
    const before = q.size;
    expectCode(() => q.append({ endPosition: [NaN, 0] }), 'MOVE_INVALID', 'endPosition[0]');
    expectCode(() => q.append({ endPosition: [0, Infinity] }), 'MOVE_INVALID', 'endPosition[1]');
    expectCode(() => q.append({ endPosition: [0, -Infinity] }), 'MOVE_INVALID', 'endPosition[1]');
    expectCode(() => q.append({ endPosition: [1, 2, 3] }), 'MOVE_DIMENSION', 'endPosition');
    expectCode(() => q.append({ endPosition: [1] }), 'MOVE_DIMENSION', 'endPosition');
    expectCode(() => q.append({ endPosition: { z: 1 } }), 'MOVE_DIMENSION', 'endPosition');
    expectCode(() => q.append({ endPosition: [5, 5], maxVelocity: 0 }), 'MOVE_INVALID', 'maxVelocity');
    expectCode(() => q.append({ endPosition: [5, 5], maxVelocity: NaN }), 'MOVE_INVALID', 'maxVelocity');
    expectCode(() => q.append({ endPosition: [5, 5], maxAcceleration: 0 }), 'MOVE_INVALID', 'maxAcceleration');
    expectCode(() => q.append({ endPosition: [5, 5], maxAcceleration: NaN }), 'MOVE_INVALID', 'maxAcceleration');
    expect(q.size).toBe(before);
    expect(q.tailPosition).toEqual([1, 1]);
  });

  it("a move's maxAcceleration caps its acceleration below the machine's, and only its own", () => {
    const q = queueOf(createMAXL(config()));
    q.append({ endPosition: [10, 0], maxAcceleration: 500 });
    q.append({ endPosition: [0, 0] });
    const segments = [q.transmitNext(0)!, q.transmitNext(0)!];
    expect(segments[0].accel).toBe(500);
    expect(segments[1].accel).toBe(3000);
    expect(Math.max(...phasesOf(segments[0].timing!).map((ph) => Math.abs(ph.a0)))).toBeCloseTo(500, 9);
    expect(Math.max(...phasesOf(segments[1].timing!).map((ph) => Math.abs(ph.a0)))).toBeCloseTo(3000, 9);
  });

  it('skips and counts zero-length moves', async () => {
    const maxl = createMAXL(config());
    await maxl.addSegmentToQueue({ endPosition: [5, 5] });
    const r = await maxl.addSegmentToQueue({ endPosition: [5, 5] });
    expect(r.skipped).toBe(true);
    expect(r.segmentIds).toEqual([]);
    await maxl.addSegmentToQueue({ endPosition: [5, 5 + 1e-12] });
    expect(maxl.skippedZeroLength).toBe(2);
    expect(maxl.queue.size).toBe(1);
  });

  it('refuses moves outside the soft limits', () => {
    const maxl = createMAXL(config({ softLimits: { x: [0, 300], y: [0, 200] } }));
    expectCode(() => queueOf(maxl).append({ endPosition: [301, 0] }), 'SOFT_LIMIT', 'endPosition.x');
    expectCode(() => queueOf(maxl).append({ endPosition: [0, -0.001] }), 'SOFT_LIMIT', 'endPosition.y');
    queueOf(maxl).append({ endPosition: [300, 200] });
    expect(maxl.queue.size).toBe(1);
  });

  it('refuses a whole move a nonlinear transform would split when any part is bad', () => {
    const maxl = createMAXL({
      motionAxes: ['x', 'y'],
      eventChannels: ['led'],
      limits: LIMITS,
      transforms: [{ type: 'function', from: ['x', 'y'], to: ['r', 'theta'], fn: ([x, y]) => [Math.hypot(x, y), Math.atan2(y, x)] }],
    });
    expectCode(() => queueOf(maxl).append({ endPosition: [50, 50], eventChannels: { nope: 1 } }), 'MOVE_INVALID', 'eventChannels.nope');
    expect(maxl.queue.size).toBe(0);
  });
});

describe('incremental planning', () => {
  const limits = resolveLimits(LIMITS, 2);
  // Short, gently turning steps (where the braking distance spans many segments
  // and lookahead matters) mixed with jumps to random points (sharp corners).
  const pathArb = fc
    .array(
      fc.oneof(
        fc.record({ kind: fc.constant('turn' as const), length: fc.double({ min: 0.05, max: 5, noNaN: true }), turn: fc.double({ min: -0.3, max: 0.3, noNaN: true }) }),
        fc.record({ kind: fc.constant('jump' as const), x: fc.double({ min: -50, max: 50, noNaN: true }), y: fc.double({ min: -50, max: 50, noNaN: true }) }),
      ),
      { minLength: 1, maxLength: 60 },
    )
    .map((steps) => {
      const points: number[][] = [];
      let at = [0, 0];
      let heading = 0;
      for (const st of steps) {
        if (st.kind === 'jump') {
          heading = Math.atan2(st.y - at[1], st.x - at[0]);
          at = [st.x, st.y];
        } else {
          heading += st.turn;
          at = [at[0] + st.length * Math.cos(heading), at[1] + st.length * Math.sin(heading)];
        }
        points.push(at);
      }
      return points;
    });

  it('never changes a plan once it is final, and final plans are optimal for the whole path', () => {
    fc.assert(
      fc.property(pathArb, (points) => {
        const maxl = createMAXL(config());
        const q = queueOf(maxl);
        const finalAt = new Map<number, [number, number]>();
        q.subscribe((e) => {
          if (e.type === 'planned') for (const s of e.segments) finalAt.set(s.id, [s.entry2, s.exit2]);
        });
        for (const p of points) q.append({ endPosition: p });
        const beforeRest = new Map(finalAt);
        q.planToRest();
        const segs = q.segments();
        for (const s of segs) {
          const early = beforeRest.get(s.id);
          if (early) expect([s.entry2, s.exit2]).toEqual(early);
        }
        const blocks = refBlocks([[0, 0], ...points], limits, []);
        const e = refJunctionSpeeds2(blocks, limits);
        segs.forEach((s, k) => {
          expect(s.entry2).toBeCloseTo(e[k], 6);
          expect(s.exit2).toBeCloseTo(e[k + 1], 6);
        });
      }),
    );
  });

  it('stays within limits, continuous and stoppable when segments are locked early', () => {
    fc.assert(
      fc.property(pathArb, fc.integer({ min: 1, max: 6 }), (points, lookahead) => {
        const maxl = createMAXL(config());
        const q = queueOf(maxl);
        const locked = [];
        for (const p of points) {
          q.append({ endPosition: p });
          while (q.untransmittedCount > lookahead) locked.push(q.transmitNext(0)!);
        }
        while (q.untransmittedCount > 0) locked.push(q.transmitNext(0)!);
        if (locked.length === 0) return;
        expect(locked[0].entry2).toBe(0);
        expect(locked[locked.length - 1].exit2).toBe(0);
        for (let k = 0; k < locked.length; k++) {
          const s = locked[k];
          if (k > 0) {
            expect(s.entry2).toBe(locked[k - 1].exit2);
            expect(s.startTime_us).toBe(locked[k - 1].endTime_us);
            expect(s.entry2).toBeLessThanOrEqual(s.maxEntry2 * (1 + 1e-9) + 1e-9);
          }
          // Reachable within the block at its acceleration, both ways.
          expect(Math.abs(s.exit2 - s.entry2)).toBeLessThanOrEqual(2 * s.accel * s.length * (1 + 1e-9) + 1e-9);
          for (const ph of phasesOf(s.timing!)) {
            expect(Math.abs(ph.a0)).toBeLessThanOrEqual(s.accel * (1 + 1e-12));
            expect(ph.v0).toBeLessThanOrEqual(Math.sqrt(s.cruise2) * (1 + 1e-12));
          }
        }
      }),
    );
  });
});

describe('splitting and braking', () => {
  const totalTime = (segs: { duration_s: number }[]) => segs.reduce((t, s) => t + s.duration_s, 0);

  it('splits the front segment without changing the plan', () => {
    const a = createMAXL(config());
    const b = createMAXL(config());
    for (const m of [a, b]) {
      queueOf(m).append({ endPosition: [100, 0] });
      queueOf(m).append({ endPosition: [100, 50] });
    }
    const [p1, p2] = queueOf(b).splitFront(30);
    expect(p1.length).toBeCloseTo(30, 12);
    expect(p2.length).toBeCloseTo(70, 12);
    expect(p2.start).toEqual([30, 0]);
    expect(p1.moveId).toBe(p2.moveId);
    for (const m of [a, b]) queueOf(m).planToRest();
    const locked = (m: typeof a) => {
      const out = [];
      for (let s = queueOf(m).transmitNext(0); s; s = queueOf(m).transmitNext(0)) out.push(s);
      return out;
    };
    const whole = locked(a);
    const split = locked(b);
    expect(split.length).toBe(3);
    expect(totalTime(split)).toBeCloseTo(totalTime(whole), 9);
    // The same motion: positions agree along the way.
    for (let t = 0; t < totalTime(whole) * 1e6; t += 7919) {
      const pa = a.sample(t).position;
      const pb = b.sample(t).position;
      expect(Math.hypot(pa[0] - pb[0], pa[1] - pb[1])).toBeLessThan(1e-6);
    }
  });

  it('brakes to rest as soon as the limits allow, on the path, and holds the rest back', () => {
    const maxl = createMAXL(config());
    const q = queueOf(maxl);
    for (let k = 1; k <= 20; k++) q.append({ endPosition: [k * 10, 0] }); // 200 mm straight, in 10 mm pieces
    q.planToRest();
    const first = [q.transmitNext(0)!, q.transmitNext(0)!, q.transmitNext(0)!];
    const v2 = first[2].exit2; // speed² the locked path leaves the machine at
    expect(v2).toBeGreaterThan(0);
    const next = q.brakeToRest()!;
    // Rest is reached v²/2a further on, exactly.
    const stopAt = first[2].end[0] + v2 / (2 * 3000);
    expect(next.start[0]).toBeCloseTo(stopAt, 9);
    expect(next.maxEntry2).toBe(0);
    // Everything up to there decelerates at the limit, and ends at rest there.
    const braking = [];
    for (let s = q.transmitNext(0); s && s !== next; s = q.transmitNext(0)) {
      braking.push(s);
      if (s.end[0] >= stopAt - 1e-9) break;
    }
    expect(braking[braking.length - 1].exit2).toBe(0);
    for (const s of braking) for (const ph of phasesOf(s.timing!)) expect(ph.a0).toBeCloseTo(-3000, 6);
    // The path after the stop is still queued, and starts from rest.
    expect(q.peekUntransmitted()).toBe(next);
    expect(q.segments().slice(-1)[0].end).toEqual([200, 0]);
  });

  it('cancels from a segment on', () => {
    const maxl = createMAXL(config());
    const q = queueOf(maxl);
    for (let k = 1; k <= 5; k++) q.append({ endPosition: [k * 10, 0] });
    const third = q.segments()[2];
    q.cancelFrom(third.id);
    expect(q.segments().length).toBe(2);
    expect(q.tailPosition).toEqual([20, 0]);
    q.transmitNext(0);
    expect(() => q.cancelFrom(q.segments()[0].id)).toThrow(/locked/);
  });
});
