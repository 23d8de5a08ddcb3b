/**
 * LineLimits (lineLimits.ts) against the functions it stands in for (moves.ts
 * lineCruise2, lineAccel, entryCap2 at a corner): the same numbers to the bit, with
 * and without per-axis limits, for random directions and move caps.
 */
import { describe, expect, it } from 'vitest';
import fc from 'fast-check';
import { resolveLimits } from '../config/limits.ts';
import { entryCap2, lineAccel, lineCruise2, ValidatedMove } from './moves.ts';
import { LineLimits } from './lineLimits.ts';

const AXES = 3;
const component = fc.double({ min: -1, max: 1, noNaN: true });
const direction = fc.tuple(component, component, component).filter(([x, y, z]) => Math.hypot(x, y, z) > 1e-6).map((v) => {
  const n = Math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return v.map((c) => c / n);
});
const perAxis = (min: number, max: number) => fc.option(fc.array(fc.double({ min, max, noNaN: true }), { minLength: AXES, maxLength: AXES }));
const cap = (min: number, max: number) => fc.option(fc.double({ min, max, noNaN: true }));

describe('LineLimits', () => {
  it("gives moves.ts's cruise cap, acceleration and corner entry cap to the bit", () => {
    fc.assert(
      fc.property(
        perAxis(10, 500),
        perAxis(100, 9000),
        direction,
        fc.option(direction),
        cap(1, 400),
        cap(100, 5000),
        fc.double({ min: 0, max: 1e5, noNaN: true }),
        (axisMaxVelocity, axisMaxAcceleration, unit, prevUnit, maxVelocity, maxAcceleration, prevCruise2) => {
          const limits = resolveLimits(
            {
              maxVelocity: 250,
              maxAcceleration: 3000,
              junctionDeviation: 0.05,
              ...(axisMaxVelocity ? { axisMaxVelocity } : {}),
              ...(axisMaxAcceleration ? { axisMaxAcceleration } : {}),
            },
            AXES,
          );
          const move = new ValidatedMove([0, 0, 0], maxVelocity ?? Infinity, [], null, maxAcceleration ?? Infinity, []);
          const line = new LineLimits(limits);
          const cruise2 = line.cruise2(move.maxVelocity, unit);
          expect(cruise2).toBe(lineCruise2(limits, move, unit));
          expect(line.accel(move.maxAcceleration, unit)).toBe(lineAccel(limits, move, unit));
          expect(line.entryCap2(prevUnit, prevCruise2, unit, cruise2)).toBe(entryCap2(limits, prevUnit, prevCruise2, unit, cruise2, true));
        },
      ),
      { numRuns: 500 },
    );
  });
});
