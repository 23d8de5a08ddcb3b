import { describe, expect, it } from 'vitest';
import { floorCruise2 } from '../trajectory/moves.ts';
import { trapezoidTiming, timingDuration } from '../plan/phases.ts';
import { bytesPerSegment, feedLimit, LINK_SHARE } from './linkFeedLimit.ts';
import fc from 'fast-check';

describe('bytes a segment costs on the wire', () => {
  it('grows by an i32 end position per position track, and a frame more where a batch no longer fits one', () => {
    const b = [1, 2, 3, 4].map(bytesPerSegment);
    for (let i = 1; i < b.length; i++) {
      expect(b[i] - b[i - 1]).toBeGreaterThanOrEqual(4);
      expect(b[i] - b[i - 1]).toBeLessThanOrEqual(4 + 12 / 4); // + at most one more frame's header, seq, type, CRC, COBS, delimiter over the batch
    }
    // GEOMETRY (length + end) and TIMING (shape, three 2-byte durations, alpha) plus framing, over a batch of 4
    expect(b[0]).toBeGreaterThan(4 + 4 + 1 + 6 + 4);
    expect(b[0]).toBeLessThan(40);
    expect(bytesPerSegment(0)).toBe(0);
  });
});

describe('the floor on segment durations', () => {
  it('comes from the slowest link and the widest subscription, and ignores links that do not say', () => {
    const limit = feedLimit([
      { device: 'fast', positionSlots: 3, bytesPerSecond: 1_000_000 },
      { device: 'uno', positionSlots: 1, bytesPerSecond: 25_000 },
      { device: 'unknown', positionSlots: 6, bytesPerSecond: undefined },
      { device: 'events only', positionSlots: 0, bytesPerSecond: 100 },
    ]);
    expect(limit.device).toBe('uno');
    expect(limit.minSegment_us).toBeCloseTo((bytesPerSegment(1) / (25_000 * LINK_SHARE)) * 1e6, 9);
    expect(feedLimit([{ device: 'sim', positionSlots: 2, bytesPerSecond: undefined }]).minSegment_us).toBe(0);
    expect(feedLimit([]).device).toBeNull();
  });

  it('as a speed cap, makes every trapezoid last at least the floor', () => {
    fc.assert(
      fc.property(
        fc.double({ min: 0.001, max: 50, noNaN: true }),
        fc.double({ min: 1, max: 500, noNaN: true }),
        fc.double({ min: 10, max: 20_000, noNaN: true }),
        fc.double({ min: 1e-5, max: 0.01, noNaN: true }),
        fc.double({ min: 0, max: 1, noNaN: true }),
        fc.double({ min: 0, max: 1, noNaN: true }),
        (length, speed, accel, floor_s, entryShare, exitShare) => {
          const cruise2 = floorCruise2(speed * speed, length, floor_s);
          expect(cruise2).toBeLessThanOrEqual(speed * speed);
          // entry and exit are at most the cap (the planner's rule), and reachable within the length
          const entry2 = Math.min(cruise2 * entryShare, 2 * accel * length);
          const exit2 = Math.min(cruise2 * exitShare, entry2 + 2 * accel * length);
          const duration = timingDuration(trapezoidTiming(length, entry2, exit2, cruise2, accel));
          expect(duration).toBeGreaterThanOrEqual(floor_s * (1 - 1e-9));
        },
      ),
    );
    expect(floorCruise2(400, 1, 0)).toBe(400);
  });
});
