import { describe, expect, it } from 'vitest';
import { DeviceClock } from './deviceClock.ts';

describe('DeviceClock', () => {
  it('applies offset and drift: micros = floor(offset + t·(1 + ppm·1e-6))', () => {
    const c = new DeviceClock({ offset_us: 1_000_000, ppm: 100 });
    expect(c.microsAt(0)).toBe(1_000_000);
    // After one author second, the device counted 1 000 100 µs.
    expect(c.microsAt(1_000_000)).toBe(2_000_100);
    // Slow clock: −50 ppm over an hour is 180 ms behind.
    const slow = new DeviceClock({ offset_us: 0, ppm: -50 });
    expect(slow.microsAt(3_600_000_000)).toBe(3_600_000_000 - 180_000);
    expect(slow.microsAt(1.9)).toBe(1);
  });

  it('wraps at 2³² µs (71.6 minutes)', () => {
    const c = new DeviceClock({ offset_us: 4294967296 - 10, ppm: 0 });
    expect(c.microsAt(9)).toBe(4294967295);
    expect(c.microsAt(10)).toBe(0);
    expect(c.microsAt(15)).toBe(5);
    // An offset past the wrap is reduced, and negative counts wrap upward.
    expect(new DeviceClock({ offset_us: 4294967296 * 3 + 7, ppm: 0 }).microsAt(0)).toBe(7);
    expect(new DeviceClock({ offset_us: -1, ppm: 0 }).microsAt(0)).toBe(4294967295);
  });

  it('inverts: authorTimeAt(deviceTimeAt(t)) = t', () => {
    const c = new DeviceClock({ offset_us: 123_456_789, ppm: -173 });
    for (const t of [0, 1, 1e6, 3.6e9]) expect(c.authorTimeAt(c.deviceTimeAt(t))).toBeCloseTo(t, 3);
  });
});
