/**
 * Properties of stroke ordering and merging, on random drawings:
 * - sorting keeps exactly the drawing's segments (as unordered point pairs), and
 *   its travel is never longer than the file's order;
 * - merging keeps every segment, adds only joins no longer than its tolerance, and
 *   never makes more paths;
 * - both keep speeds and dwells with their segments and points.
 */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { mergePaths, sortPaths } from './ordering.ts';
import { travelLength, type PlotPath } from './paths.ts';

const coord = fc.integer({ min: 0, max: 400 }).map((v) => v / 4); // 0.25 mm grid, so ends touch often

const pathArb: fc.Arbitrary<PlotPath> = fc
  .record({
    xy: fc.array(fc.tuple(coord, coord), { minLength: 2, maxLength: 6 }),
    speeds: fc.boolean(),
    dwells: fc.boolean(),
  })
  .map(({ xy, speeds, dwells }) => ({
    points: Float64Array.from(xy.flat()),
    // Each segment's speed and each point's dwell encode where they belong, to follow them through reversals.
    speeds: speeds ? Float64Array.from(xy.slice(1), (_, i) => 1 + segmentCode(xy[i], xy[i + 1])) : null,
    dwells: dwells ? Float64Array.from(xy, ([x, y]) => 1 + x * 1000 + y) : null,
  }));

const drawing = fc.array(pathArb, { minLength: 0, maxLength: 30 });
const start = fc.tuple(coord, coord);

/** A symmetric code of a segment's two ends. */
function segmentCode(a: readonly number[], b: readonly number[]): number {
  const [p, q] = [a[0] * 1000 + a[1], b[0] * 1000 + b[1]].sort((u, v) => u - v);
  return p * 7 + q * 13;
}

/** The drawing's segments as unordered point pairs, a multiset (sorted keys). */
function segments(paths: readonly PlotPath[]): string[] {
  const out: string[] = [];
  for (const p of paths) {
    for (let i = 2; i < p.points.length; i += 2) {
      const a = `${p.points[i - 2]},${p.points[i - 1]}`, b = `${p.points[i]},${p.points[i + 1]}`;
      out.push(a < b ? `${a}|${b}` : `${b}|${a}`);
    }
  }
  return out.sort();
}

/** Each segment's speed checked against the code of its ends. */
function speedsFollowSegments(paths: readonly PlotPath[]): boolean {
  for (const p of paths) {
    if (!p.speeds) continue;
    for (let i = 0; i + 1 < p.points.length / 2; i++) {
      const v = p.speeds[i];
      if (v === 0) continue; // a join's own segment
      const a = [p.points[2 * i], p.points[2 * i + 1]], b = [p.points[2 * i + 2], p.points[2 * i + 3]];
      if (v !== 1 + segmentCode(a, b)) return false;
    }
  }
  return true;
}

describe('sortPaths', () => {
  it('keeps exactly the same segments, and never travels farther than the file’s order', () => {
    fc.assert(
      fc.property(drawing, start, (paths, from) => {
        const sorted = sortPaths(paths, from);
        expect(sorted).toHaveLength(paths.length);
        expect(segments(sorted)).toEqual(segments(paths));
        expect(travelLength(sorted, from)).toBeLessThanOrEqual(travelLength(paths, from) + 1e-9);
        expect(speedsFollowSegments(sorted)).toBe(true);
      }),
      { numRuns: 300 },
    );
  });

  it('finds the obvious order: strokes along a line, shuffled and reversed, need no travel but to the first', () => {
    fc.assert(
      fc.property(fc.shuffledSubarray([...Array(12).keys()], { minLength: 12, maxLength: 12 }), fc.array(fc.boolean(), { minLength: 12, maxLength: 12 }), (order, flips) => {
        const paths = order.map((k, i) => ({ points: Float64Array.from(flips[i] ? [k + 1, 0, k, 0] : [k, 0, k + 1, 0]), speeds: null, dwells: null }));
        expect(travelLength(sortPaths(paths, [0, 0]), [0, 0])).toBe(0);
      }),
    );
  });


  it('keeps the file’s order where greedy nearest neighbour would travel farther', () => {
    // From 0, greedy takes 1 first, then 3 and 5, and comes back for −1.1 (11.1 mm); the file goes left first (7.2 mm).
    const dot = (x: number) => ({ points: Float64Array.from([x, 0, x, 0.001]), speeds: null, dwells: null });
    const paths = [dot(-1.1), dot(1), dot(3), dot(5)];
    const sorted = sortPaths(paths, [0, 0]);
    expect(sorted.map((p) => p.points[0])).toEqual([-1.1, 1, 3, 5]);
  });
});

describe('mergePaths', () => {
  it('keeps every segment, adds only joins ≤ the tolerance, and never makes more paths', () => {
    fc.assert(
      fc.property(drawing, fc.constantFrom(0, 0.25, 1), (paths, tol) => {
        const merged = mergePaths(paths, tol);
        expect(merged.length).toBeLessThanOrEqual(paths.length);
        const before = segments(paths);
        const after = segments(merged);
        // Every original segment is still there (as a multiset)…
        const left = new Map<string, number>();
        for (const s of after) left.set(s, (left.get(s) ?? 0) + 1);
        for (const s of before) {
          expect(left.get(s) ?? 0).toBeGreaterThan(0);
          left.set(s, (left.get(s) as number) - 1);
        }
        // …and what is new is one join per merge, no longer than the tolerance.
        let joins = 0;
        for (const [s, n] of left) {
          if (n === 0) continue;
          const [a, b] = s.split('|').map((p) => p.split(',').map(Number));
          expect(Math.hypot(a[0] - b[0], a[1] - b[1])).toBeLessThanOrEqual(tol + 1e-9);
          joins += n;
        }
        expect(joins).toBeLessThanOrEqual(paths.length - merged.length);
        expect(speedsFollowSegments(merged)).toBe(true);
        // Dwells stay at their points (a touch adds both of its points' holds).
        const total = (ps: readonly PlotPath[]) => ps.reduce((s, p) => s + (p.dwells ? p.dwells.reduce((u, v) => u + v, 0) : 0), 0);
        expect(total(merged)).toBeCloseTo(total(paths), 6);
      }),
      { numRuns: 300 },
    );
  });

  it('joins a chain given backwards and scrambled into one path', () => {
    const paths = [
      [2, 0, 3, 0],
      [1, 0, 0, 0],
      [2, 0, 1, 0],
    ].map((xy) => ({ points: Float64Array.from(xy), speeds: null, dwells: null }));
    const merged = mergePaths(paths, 0);
    expect(merged).toHaveLength(1);
    expect(Array.from(merged[0].points)).toEqual([0, 0, 1, 0, 2, 0, 3, 0]);
  });
});
