/**
 * The grid's nearest free end is a brute-force scan's (the same distance), within
 * a radius too, as ends are removed.
 */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { EndpointGrid } from './endpointGrid.ts';

// µm steps over a bed and beyond it; ends may coincide.
const coord = fc.integer({ min: -50_000, max: 150_000 }).map((v) => v / 1000);

describe('EndpointGrid', () => {
  it('finds the nearest free end within a radius, as a scan does, while ends are removed', () => {
    fc.assert(
      fc.property(
        fc.array(fc.tuple(coord, coord), { minLength: 1, maxLength: 60 }),
        fc.array(fc.tuple(coord, coord, fc.constantFrom(Infinity, 0.5, 5, 40)), { minLength: 1, maxLength: 20 }),
        (ends, queries) => {
          const xy = Float64Array.from(ends.flat());
          const grid = new EndpointGrid(xy);
          const free = new Set(ends.map((_, i) => i));
          for (const [x, y, radius] of queries) {
            let want = Infinity;
            for (const id of free) want = Math.min(want, Math.hypot(xy[2 * id] - x, xy[2 * id + 1] - y));
            const got = grid.nearest(x, y, radius);
            if (free.size === 0 || want > radius) expect(got).toBe(-1);
            else {
              expect(free.has(got)).toBe(true);
              expect(Math.hypot(xy[2 * got] - x, xy[2 * got + 1] - y)).toBeCloseTo(want, 9);
              grid.remove(got);
              free.delete(got);
            }
          }
        },
      ),
      { numRuns: 400 },
    );
  });
});
