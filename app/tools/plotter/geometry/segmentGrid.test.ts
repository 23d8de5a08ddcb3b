/**
 * The grid's nearest-segment distance is the full scan's, exactly, for any drawing
 * and any point (inside the drawing's box or far outside it), and the Hausdorff
 * distance through it behaves as the definition says.
 */
import { describe, expect, it } from 'vitest';
import fc from 'fast-check';
import { hausdorff, pointDrawingDistance } from './hausdorff.ts';
import { SegmentGrid } from './segmentGrid.ts';

const coordinate = fc.double({ min: -200, max: 200, noNaN: true });
/** Polylines of 1 (a lone point) to 40 points, some with long jumps, some dense. */
const polyline = fc.array(fc.tuple(coordinate, coordinate), { minLength: 1, maxLength: 40 }).map((p) => Float64Array.from(p.flat()));
const drawing = fc.array(polyline, { minLength: 0, maxLength: 6 });
const point = fc.tuple(fc.double({ min: -1000, max: 1000, noNaN: true }), fc.double({ min: -1000, max: 1000, noNaN: true }));

describe('SegmentGrid', () => {
  it('gives the same distance as scanning every segment, bit for bit', () => {
    fc.assert(
      fc.property(drawing, fc.array(point, { minLength: 1, maxLength: 30 }), (d, ps) => {
        const grid = new SegmentGrid(d);
        for (const [x, y] of ps) expect(grid.distance(x, y)).toBe(pointDrawingDistance(x, y, d));
      }),
      { numRuns: 300 },
    );
  });

  it('agrees on a dense curve, at points near it (where the ring search stops early)', () => {
    const n = 2000;
    const curve = new Float64Array(2 * (n + 1));
    for (let i = 0; i <= n; i++) {
      curve[2 * i] = 50 + 30 * Math.cos((3 * Math.PI * i) / n);
      curve[2 * i + 1] = 50 + 20 * Math.sin((3 * Math.PI * i) / n);
    }
    const grid = new SegmentGrid([curve]);
    for (let k = 0; k < 2000; k++) {
      const x = 15 + (k % 50) * 1.4;
      const y = 25 + Math.floor(k / 50) * 1.25;
      expect(grid.distance(x, y)).toBe(pointDrawingDistance(x, y, [curve]));
    }
  });

  it('an empty drawing is infinitely far; the Hausdorff distance of two offset lines is their offset', () => {
    expect(new SegmentGrid([]).distance(1, 2)).toBe(Infinity);
    expect(hausdorff([[0, 0, 10, 0]], [[0, 0.5, 10, 0.5]], 0.01)).toBeCloseTo(0.5, 12);
    // A stroke 1 mm too long: the extra end is 1 mm from the shorter one.
    expect(hausdorff([[0, 0, 11, 0]], [[0, 0, 10, 0]], 0.01)).toBeCloseTo(1, 12);
  });
});
