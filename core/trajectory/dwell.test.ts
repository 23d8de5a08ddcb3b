/**
 * Dwells and event-only moves in the queue: validation, planning (rest before and
 * after, exact duration), what an evaluator sees, edits around a dwell, braking.
 */
import { describe, expect, it } from 'vitest';
import { createMAXL, MAX_DWELL_S, MaxlError, planPath, type EvaluatorState, type MaxlConfig, type Move } from '../index.ts';
import { queueOf } from '../maxl.ts';

const config = (extra: Partial<MaxlConfig> = {}): MaxlConfig => ({
  motionAxes: ['x', 'y'],
  eventChannels: ['pen', 'laser'],
  limits: { maxVelocity: 200, maxAcceleration: 2000, junctionDeviation: 0.05 },
  ...extra,
});

function expectRefused(fn: () => unknown, field: string, message?: RegExp): MaxlError {
  let caught: unknown;
  try {
    fn();
  } catch (err) {
    caught = err;
  }
  expect(caught).toBeInstanceOf(MaxlError);
  const e = caught as MaxlError;
  expect(e.code).toBe('MOVE_INVALID');
  expect(e.field).toBe(field);
  if (message) expect(e.message).toMatch(message);
  return e;
}

describe('dwell validation', () => {
  it('refuses a dwell that also gives an end position or a speed, naming the field, and changes nothing', () => {
    const q = queueOf(createMAXL(config()));
    q.append({ endPosition: [10, 0] });
    const before = q.size;
    expectRefused(() => q.append({ dwell_s: 1, endPosition: [5, 5] } as Move), 'endPosition', /no endPosition/);
    expectRefused(() => q.append({ dwell_s: 1, maxVelocity: 10 } as Move), 'maxVelocity', /no maxVelocity/);
    expect(q.size).toBe(before);
    expect(q.tailPosition).toEqual([10, 0]);
  });

  it('refuses a duration that is negative, not finite, not a number, or longer than the wire times', () => {
    const q = queueOf(createMAXL(config()));
    for (const bad of [-0.001, NaN, Infinity, '1' as unknown as number, undefined as unknown as number]) {
      expectRefused(() => q.append({ dwell_s: bad }), 'dwell_s');
    }
    expectRefused(() => q.append({ dwell_s: MAX_DWELL_S + 0.001 }), 'dwell_s', /at most 2000 s/);
    expect(q.size).toBe(0);
    expect(q.append({ dwell_s: MAX_DWELL_S }).skipped).toBe(false);
  });

  it('resolves its events like a linear move’s, and refuses an unknown channel', () => {
    const q = queueOf(createMAXL(config()));
    expectRefused(() => q.append({ dwell_s: 0.1, eventChannels: { spindle: 1 } }), 'eventChannels.spindle', /not an event channel/);
    expectRefused(() => q.append({ dwell_s: 0.1, eventChannels: { pen: NaN } }), 'eventChannels.pen');
    expect(q.size).toBe(0);
  });

  it('is refused by addSegmentToQueue with a rejected promise, nothing enqueued', async () => {
    const maxl = createMAXL(config());
    await expect(maxl.addSegmentToQueue({ dwell_s: -1 })).rejects.toMatchObject({ code: 'MOVE_INVALID', field: 'dwell_s' });
    expect(maxl.queue.size).toBe(0);
  });
});

describe('dwell planning', () => {
  it('plans to rest before a dwell and from rest after it, and lasts exactly dwell_s at rest', () => {
    const q = queueOf(createMAXL(config()));
    q.append({ endPosition: [50, 0] });
    const dwell = q.append({ dwell_s: 0.12, eventChannels: { pen: 1 } });
    // Straight on after the dwell: without it, the junction would be taken at full speed.
    q.append({ endPosition: [100, 0] });
    q.planToRest();
    const [a, d, b] = q.segments();
    expect(d.id).toBe(dwell.segmentIds[0]);
    expect(a.exit2).toBe(0);
    expect([d.entry2, d.exit2, d.length]).toEqual([0, 0, 0]);
    expect(d.start).toEqual([50, 0]);
    expect(d.end).toEqual([50, 0]);
    expect(d.unit).toEqual([0, 0]);
    expect(d.timing).toEqual([0, 0.12, 0, 0, 0, 0]);
    expect(d.duration_s).toBe(0.12);
    expect(b.entry2).toBe(0);
    expect(b.maxEntry2).toBe(0);
    // The machine rests through the dwell, in the author's own record too.
    const maxl = createMAXL(config());
    queueOf(maxl).append({ endPosition: [50, 0] });
    queueOf(maxl).append({ dwell_s: 0.12 });
    queueOf(maxl).append({ endPosition: [100, 0] });
    queueOf(maxl).planToRest();
    const [s1, s2] = [queueOf(maxl).transmitNext(0)!, queueOf(maxl).transmitNext(0)!];
    expect(s2.startTime_us).toBe(s1.endTime_us);
    for (const f of [0, 0.3, 0.99]) {
      const sample = maxl.history.sample(s2.startTime_us + f * 0.12e6)!;
      expect(sample.position).toEqual([50, 0]);
      expect(sample.speed).toBe(0);
      expect(sample.velocity.map(Math.abs)).toEqual([0, 0]);
    }
  });

  it('holds wherever the path is when a move before it is cancelled or replaced', () => {
    const q = queueOf(createMAXL(config()));
    q.append({ endPosition: [10, 0] });
    const second = q.append({ endPosition: [10, 30] });
    q.append({ dwell_s: 0.5 });
    q.append({ endPosition: [40, 30] });
    q.cancel(second.moveId);
    let d = q.segments().find((s) => s.isDwell)!;
    expect(d.start).toEqual([10, 0]);
    const next = q.segments()[q.segments().indexOf(d) + 1];
    expect(next.start).toEqual([10, 0]);
    expect(next.maxEntry2).toBe(0);
    q.replace(q.segments()[0].moveId, { endPosition: [20, 5] });
    d = q.segments().find((s) => s.isDwell)!;
    expect(d.start).toEqual([20, 5]);
    q.planToRest();
    expect(d.duration_s).toBe(0.5);
  });

  it('shows an evaluator distance 0, speed 0 and a zero direction, over the dwell’s time', () => {
    const q = queueOf(createMAXL(config()));
    const seen: EvaluatorState[] = [];
    q.append({ endPosition: [30, 40] });
    q.append({
      dwell_s: 0.05,
      eventChannels: [{ name: 'laser', evaluationPrecision: 10, evaluator: (s) => (seen.push(s), s.time * 100) }],
    });
    q.planToRest();
    q.transmitNext(0);
    const d = q.transmitNext(0)!;
    const [track] = q.eventTracksOf(d);
    expect(seen.length).toBe(5);
    for (const s of seen) {
      expect(s.distance).toBe(0);
      expect(s.moveDistance).toBe(0);
      expect(s.speed).toBe(0);
      expect(s.unit).toEqual([0, 0]);
      expect(s.velocity.map(Math.abs)).toEqual([0, 0]);
      expect(s.acceleration.map(Math.abs)).toEqual([0, 0]);
      expect(s.position).toEqual({ x: 30, y: 40 });
      expect(s.duration).toBe(0.05);
    }
    expect(track.times).toEqual(seen.map((s) => s.time));
  });

  it('brings a pause to rest before a dwell, its events not yet set', () => {
    const q = queueOf(createMAXL(config()));
    q.append({ endPosition: [1, 0] });
    q.append({ dwell_s: 0.2, eventChannels: { pen: 1 } });
    q.append({ endPosition: [100, 0] });
    q.planToRest();
    q.transmitNext(0);
    const hold = q.brakeToRest();
    expect(hold?.isDwell).toBe(true);
  });
});

describe('event-only moves', () => {
  it('are a dwell of 0 s: their events happen, between the segments around them', () => {
    const maxl = createMAXL(config());
    const q = queueOf(maxl);
    q.append({ endPosition: [20, 0] });
    const r = q.append({ endPosition: [20, 0], eventChannels: { pen: 1 } });
    expect(r.skipped).toBe(false);
    expect(r.segmentIds.length).toBe(1);
    q.append({ endPosition: [40, 0] });
    q.planToRest();
    expect(maxl.skippedZeroLength).toBe(0);
    const [a, e, b] = [q.transmitNext(0)!, q.transmitNext(0)!, q.transmitNext(0)!];
    expect(e.isDwell).toBe(true);
    expect(e.duration_s).toBe(0);
    expect(a.exit2).toBe(0); // the machine stops for it
    expect(e.startTime_us).toBe(a.endTime_us);
    expect(b.startTime_us).toBe(e.endTime_us);
    expect(q.eventTracksOf(e)).toEqual([{ channel: 0, times: [0], values: [1] }]);
    expect(maxl.eventValue('pen', a.endTime_us - 1)).toBe(0);
    expect(maxl.eventValue('pen', e.startTime_us)).toBe(1);
    expect(maxl.eventValue('pen', b.endTime_us)).toBe(1);
  });

  it('a dwell of 0 s given as such is one too; a zero-length move with no events is still skipped', () => {
    const maxl = createMAXL(config());
    const q = queueOf(maxl);
    expect(q.append({ dwell_s: 0, eventChannels: { laser: 0.5 } }).skipped).toBe(false);
    expect(q.append({ endPosition: [0, 0] }).skipped).toBe(true);
    expect(maxl.skippedZeroLength).toBe(1);
    expect(q.size).toBe(1);
  });
});

describe('planPath with dwells', () => {
  const limits = { maxVelocity: 200, maxAcceleration: 2000 };
  it('plans { dwell_s } as a segment at rest and holds position through it', () => {
    const p = planPath([0, 0], [{ end: [10, 0] }, { dwell_s: 0.25 }, { end: [10, 10] }, { dwell_s: 0 }], limits);
    expect(p.segments.map((s) => s.dwell)).toEqual([false, true, false, true]);
    const d = p.segments[1];
    expect(d).toMatchObject({ start: [10, 0], end: [10, 0], length: 0, duration: 0.25, entryVelocity: 0, exitVelocity: 0, peakVelocity: 0 });
    expect(p.segments[0].exitVelocity).toBe(0);
    expect(p.segments[2].entryVelocity).toBe(0);
    expect(p.segments[2].startTime).toBe(d.startTime + 0.25);
    expect(p.duration).toBeCloseTo(p.segments[0].duration + 0.25 + p.segments[2].duration, 12);
    const mid = p.sample(d.startTime + 0.1);
    expect(mid.position).toEqual([10, 0]);
    expect(mid.velocity.map(Math.abs)).toEqual([0, 0]);
  });

  it('refuses a bad dwell naming the move, and a bad floor', () => {
    expect(() => planPath([0, 0], [{ end: [1, 0] }, { dwell_s: -2 }], limits)).toThrow(expect.objectContaining({ code: 'MOVE_INVALID', field: 'moves[1].dwell_s' }));
    expect(() => planPath([0, 0], [{ dwell_s: 1, end: [1, 1] } as never], limits)).toThrow(/no end\b/);
    expect(() => planPath([0, 0], [], limits, { minSegment_us: -1 })).toThrow(expect.objectContaining({ field: 'options.minSegment_us' }));
  });

  it('applies a link’s duration floor when given one', () => {
    // 0.2 mm steps: far faster than a 5 ms floor allows (0.2 mm / 5 ms = 40 mm/s).
    const moves = Array.from({ length: 50 }, (_, i) => ({ end: [0.2 * (i + 1), 0] }));
    const free = planPath([0, 0], moves, limits);
    const floored = planPath([0, 0], moves, limits, { minSegment_us: 5_000 });
    expect(free.segments.some((s) => s.duration < 0.005)).toBe(true);
    for (const s of floored.segments) expect(s.duration).toBeGreaterThanOrEqual(0.005 - 1e-12);
    expect(floored.duration).toBeGreaterThan(free.duration);
  });

  it('keeps a floor on sub-µm segments, where the junction speed is tiny beside the work before it', () => {
    // Found by the planPath floor property at 6 000 runs: a 27 nm line then a 2.7 nm one straight
    // on, each capped to ~1.7e-6 and ~1.7e-7 mm/s by a 15.7 ms floor. The lookahead's bound
    // (cap + 2W) − 2W rounded 4e-8 above the second line's cap v² ≈ 3e-14, so it cruised above
    // its floor speed and lasted 1.57e-11 s less than the floor.
    const floor_us = 15720.370845607169;
    const p = planPath([0, 0, 0], [{ end: [0, -2.7258327910444166e-8, 0] }, { end: [0, -2.998416070148858e-8, 0] }], {
      junctionDeviation: 0.001,
      maxVelocity: 5,
      maxAcceleration: 279.8922426838547,
    }, { minSegment_us: floor_us });
    expect(p.segments.length).toBe(2);
    for (const s of p.segments) {
      expect(s.duration).toBeGreaterThanOrEqual(floor_us * 1e-6);
      // The floor's speed, length / floor, is the cap, and no phase goes above it.
      expect(s.peakVelocity).toBeLessThanOrEqual(s.length / (floor_us * 1e-6));
    }
  });
});
