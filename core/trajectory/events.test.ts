import { describe, expect, it } from 'vitest';
import { createMAXL, MaxlError, type EvaluatorState } from '../index.ts';
import { queueOf } from '../maxl.ts';

const base = {
  motionAxes: ['x', 'y'],
  eventChannels: ['powerOut', 'neopixelBitmap'],
  limits: { maxVelocity: 100, maxAcceleration: 1000 },
  transforms: [{ type: 'corexy' as const, from: ['x', 'y'], to: ['a', 'b'] }],
};

describe('event channels', () => {
  it('holds a fixed value for the segment, and keeps the last value where a move sets none', () => {
    const maxl = createMAXL(base);
    const q = queueOf(maxl);
    q.append({ endPosition: [10, 0], eventChannels: { powerOut: 0.8 } });
    q.append({ endPosition: [20, 0] });
    q.append({ endPosition: [30, 0], eventChannels: { powerOut: 0 } });
    q.planToRest();
    const [a, b, c] = [q.transmitNext(0)!, q.transmitNext(0)!, q.transmitNext(0)!];
    expect(q.eventTracksOf(a)).toEqual([{ channel: 0, times: [0], values: [0.8] }]);
    expect(q.eventTracksOf(b)).toEqual([]);
    expect(maxl.eventValue('powerOut', -1)).toBe(0);
    expect(maxl.eventValue('powerOut', a.startTime_us)).toBe(0.8);
    expect(maxl.eventValue('powerOut', (b.startTime_us + b.endTime_us) / 2)).toBe(0.8);
    expect(maxl.eventValue('powerOut', c.startTime_us)).toBe(0);
    expect(maxl.eventValue('neopixelBitmap', c.startTime_us)).toBe(0);
    expect(maxl.trackValue('powerOut', a.startTime_us + 1)).toBe(0.8);
  });

  it('samples an evaluator every evaluationPrecision ms and keeps only the changes', () => {
    const maxl = createMAXL(base);
    const q = queueOf(maxl);
    const calls: EvaluatorState[] = [];
    // Light painting: a bit per 5 mm stripe of x.
    q.append({
      endPosition: [50, 0],
      maxVelocity: 50,
      eventChannels: [
        {
          name: 'neopixelBitmap',
          evaluationPrecision: 10,
          evaluator: (state) => {
            calls.push(state);
            return Math.floor(state.position.x / 5) % 2 === 0 ? 0xff : 0x00;
          },
        },
      ],
    });
    q.planToRest();
    const seg = q.transmitNext(0)!;
    const [track] = q.eventTracksOf(seg);
    const duration = seg.duration_s;
    // One call per 10 ms tick from 0 up to (not including) the end.
    expect(calls.length).toBe(Math.ceil(duration / 0.01 - 1e-9));
    calls.forEach((c, k) => expect(c.time).toBeCloseTo(k * 0.01, 12));
    // Only changes are kept, alternating, starting with the value at t = 0.
    expect(track.values[0]).toBe(0xff);
    for (let k = 1; k < track.values.length; k++) expect(track.values[k]).not.toBe(track.values[k - 1]);
    expect(track.values.length).toBeGreaterThan(5);
    expect(track.values.length).toBeLessThan(calls.length);
    // Each change is at the first sample whose x is in the next stripe.
    for (let k = 1; k < track.times.length; k++) {
      const x = maxl.sample(seg.startTime_us + track.times[k] * 1e6).position[0];
      const xBefore = maxl.sample(seg.startTime_us + (track.times[k] - 0.01) * 1e6).position[0];
      expect(Math.floor(x / 5)).toBe(Math.floor(xBefore / 5) + 1);
    }
  });

  it('gives evaluators the full state: positions by name, velocity, acceleration, distance, unit', () => {
    const maxl = createMAXL(base);
    const q = queueOf(maxl);
    const states: EvaluatorState[] = [];
    q.append({
      endPosition: [30, 40],
      // 47 ms keeps samples off the phase boundaries, where acceleration jumps.
      eventChannels: [{ name: 'powerOut', evaluationPrecision: 47, evaluator: (s) => (states.push(s), 1) }],
    });
    q.planToRest();
    const seg = q.transmitNext(0)!;
    q.eventTracksOf(seg);
    expect(states.length).toBeGreaterThan(2);
    for (const s of states) {
      const at = maxl.sample(seg.startTime_us + s.time * 1e6);
      expect(s.position.x).toBeCloseTo(at.position[0], 9);
      expect(s.position.y).toBeCloseTo(at.position[1], 9);
      expect(s.position.a).toBeCloseTo(at.position[0] + at.position[1], 9);
      expect(s.position.b).toBeCloseTo(at.position[0] - at.position[1], 9);
      expect(s.velocity[0]).toBeCloseTo(at.velocity[0], 9);
      expect(s.acceleration[1]).toBeCloseTo(at.acceleration[1], 9);
      expect(s.distance).toBeCloseTo(Math.hypot(at.position[0], at.position[1]), 9);
      expect(s.unit).toEqual([0.6, 0.8]);
      expect(s.speed).toBeCloseTo(Math.hypot(...at.velocity), 9);
      expect(s.duration).toBeCloseTo(seg.duration_s, 12);
    }
  });

  it('refuses unknown channels and bad values at once, and surfaces a failing evaluator before locking', () => {
    const maxl = createMAXL(base);
    const q = queueOf(maxl);
    expect(() => q.append({ endPosition: [1, 0], eventChannels: { laser: 1 } })).toThrow(/not an event channel/);
    expect(() => q.append({ endPosition: [1, 0], eventChannels: { powerOut: NaN } })).toThrow(MaxlError);
    expect(() =>
      q.append({ endPosition: [1, 0], eventChannels: [{ name: 'powerOut', evaluationPrecision: 0, evaluator: () => 1 }] }),
    ).toThrow(/evaluationPrecision/);
    expect(q.size).toBe(0);
    q.append({
      endPosition: [10, 0],
      eventChannels: [{ name: 'powerOut', evaluationPrecision: 5, evaluator: (s) => (s.time > 0.02 ? Number.NaN : 1) }],
    });
    q.planToRest();
    let err: unknown;
    try {
      q.transmitNext(0);
    } catch (e) {
      err = e;
    }
    expect(err).toBeInstanceOf(MaxlError);
    expect((err as MaxlError).field).toBe('eventChannels.powerOut');
    expect((err as MaxlError).message).toMatch(/returned NaN at t = 0\.02/);
    expect(q.segments()[0].state).toBe('planned'); // nothing was locked
  });
});
