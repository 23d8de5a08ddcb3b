import { describe, expect, it } from 'vitest';
import fc from 'fast-check';
import { DistanceThinner, type Point } from './thinning.ts';

describe('distance thinning', () => {
  it('keeps the first point, then only points at least the tolerance from the last kept one', () => {
    const t = new DistanceThinner(0.2);
    const kept = ([[0, 0], [0.1, 0], [0.19, 0], [0.2, 0], [0.3, 0], [0.5, 0]] as Point[]).filter((p) => t.push(p));
    expect(kept).toEqual([[0, 0], [0.2, 0], [0.5, 0]]);
  });

  it('ends the stroke where the pointer lifted', () => {
    const t = new DistanceThinner(0.2);
    t.push([0, 0]);
    t.push([0.05, 0]);
    t.push([0.1, 0]);
    expect(t.finish()).toEqual([0.1, 0]);
    expect(t.finish()).toBeNull();
    const u = new DistanceThinner(0.2);
    u.push([0, 0]);
    u.push([1, 0]);
    expect(u.finish()).toBeNull();
  });

  it('every dropped point lies within the tolerance of the kept polyline, and kept points are ≥ tolerance apart', () => {
    const point = fc.tuple(fc.double({ min: -50, max: 50, noNaN: true }), fc.double({ min: -50, max: 50, noNaN: true }));
    fc.assert(
      fc.property(fc.array(point, { minLength: 1, maxLength: 200 }), fc.double({ min: 0.01, max: 5, noNaN: true }), (points, tol) => {
        const t = new DistanceThinner(tol);
        const kept: Point[] = [];
        let lastKept: Point | null = null;
        for (const p of points) {
          if (t.push(p)) {
            if (lastKept) expect(Math.hypot(p[0] - lastKept[0], p[1] - lastKept[1])).toBeGreaterThanOrEqual(tol);
            kept.push(p);
            lastKept = p;
          } else {
            expect(Math.hypot(p[0] - lastKept![0], p[1] - lastKept![1])).toBeLessThan(tol);
          }
        }
        const end = t.finish();
        if (end) kept.push(end);
        expect(kept.at(-1)).toEqual(points.at(-1));
      }),
    );
  });

  it('refuses a tolerance that is not a distance', () => {
    expect(() => new DistanceThinner(-1)).toThrow(/≥ 0 mm/);
    expect(() => new DistanceThinner(NaN)).toThrow(/≥ 0 mm/);
  });
});
