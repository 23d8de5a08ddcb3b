/**
 * RecentWorst's sliding-window maximum against the plain definition: the largest
 * value noted within the window ending now, and not before a given time.
 */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { RecentWorst } from './recentWorst.ts';

describe('RecentWorst', () => {
  it('is the worst lateness of the timers in the window, and 0 once they have left it', () => {
    const lag = new RecentWorst(1_000);
    expect(lag.worst(0)).toBe(0);
    lag.noteLateness(100, 130); // 30 late
    lag.noteLateness(200, 210); // 10 late
    expect(lag.worst(210)).toBe(30);
    // Only what was noted since a time.
    expect(lag.worst(210, 131)).toBe(10);
    expect(lag.worst(210, 211)).toBe(0);
    // A timer that came early counts as on time.
    lag.noteLateness(400, 390);
    expect(lag.worst(1_130)).toBe(30);
    expect(lag.worst(1_131)).toBe(10);
    expect(lag.worst(1_391)).toBe(0);
  });

  it('agrees with the maximum over the window and since any time, for any notes', () => {
    const step = fc.record({ gap: fc.integer({ min: 0, max: 400 }), value: fc.integer({ min: 0, max: 500 }), probe: fc.integer({ min: 0, max: 300 }), since: fc.integer({ min: -2_500, max: 100 }) });
    fc.assert(
      fc.property(fc.integer({ min: 1, max: 2_000 }), fc.array(step, { maxLength: 300 }), (window_us, steps) => {
        const worst = new RecentWorst(window_us);
        const seen: Array<{ at: number; value: number }> = [];
        let clock = 0;
        for (const s of steps) {
          clock += s.gap;
          worst.note(clock, s.value);
          seen.push({ at: clock, value: s.value });
          const probe = clock + s.probe;
          const since = probe + s.since;
          const expected = Math.max(0, ...seen.filter((n) => n.at >= probe - window_us && n.at >= since).map((n) => n.value));
          if (worst.worst(probe, since) !== expected) return false;
          clock = probe;
        }
        return true;
      }),
      { numRuns: 300 },
    );
  });
});
