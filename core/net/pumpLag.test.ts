/**
 * PumpLag's sliding-window maximum against the plain definition: the largest
 * lateness of the pumps that ran within the window ending now.
 */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { PumpLag } from './pumpLag.ts';

describe('PumpLag', () => {
  it('is the worst lateness of the pumps in the window, and 0 once they have left it', () => {
    const lag = new PumpLag(1_000);
    expect(lag.worst_us(0)).toBe(0);
    lag.note(100, 130); // 30 late
    lag.note(200, 210); // 10 late
    expect(lag.worst_us(210)).toBe(30);
    // A pump that came early counts as on time.
    lag.note(400, 390);
    expect(lag.worst_us(1_130)).toBe(30);
    expect(lag.worst_us(1_131)).toBe(10);
    expect(lag.worst_us(1_391)).toBe(0);
  });

  it('agrees with the maximum over the window, for any pumps', () => {
    const pump = fc.record({ gap: fc.integer({ min: 0, max: 400 }), late: fc.integer({ min: -50, max: 500 }), probe: fc.integer({ min: 0, max: 300 }) });
    fc.assert(
      fc.property(fc.integer({ min: 1, max: 2_000 }), fc.array(pump, { maxLength: 300 }), (window_us, pumps) => {
        const lag = new PumpLag(window_us);
        const seen: Array<{ at: number; late: number }> = [];
        let due = 0;
        let clock = 0;
        for (const p of pumps) {
          due = Math.max(due + p.gap, clock);
          const at = due + p.late;
          clock = Math.max(clock, at);
          lag.note(due, clock);
          seen.push({ at: clock, late: Math.max(0, clock - due) });
          const probe = clock + p.probe;
          const expected = Math.max(0, ...seen.filter((s) => s.at >= probe - window_us).map((s) => s.late));
          if (lag.worst_us(probe) !== expected) return false;
          clock = probe;
        }
        return true;
      }),
      { numRuns: 300 },
    );
  });
});
