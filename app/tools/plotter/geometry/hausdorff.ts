/**
 * The Hausdorff distance between two drawings (sets of polylines, x,y pairs in
 * mm): the farthest any point of either lies from the other,
 *   H(A, B) = max( sup_{a ∈ A} d(a, B), sup_{b ∈ B} d(b, A) ).
 * Each polyline is a continuous curve, not its vertices: d(p, B) is the distance
 * to the nearest segment of B, and the sup over a polyline A is taken over A's
 * vertices and points every `step_mm` along its segments (the distance to B is
 * 1-Lipschitz along A, so this underestimates the sup by at most step_mm / 2).
 *
 * The nearest segment is found through a grid (segmentGrid.ts), which gives the
 * same distance as scanning every segment, only faster.
 *
 * The tests and the draw bench use it to compare a stroke with the simulated ink.
 */
import { pointSegmentDistance, SegmentGrid, type Polyline } from './segmentGrid.ts';

export { pointSegmentDistance, type Polyline };

/** Distance from a point to the nearest segment (or lone point) of any polyline in `to` (a scan of every segment; SegmentGrid answers many such questions faster). */
export function pointDrawingDistance(px: number, py: number, to: readonly Polyline[]): number {
  let best = Infinity;
  for (const line of to) {
    if (line.length === 2) best = Math.min(best, Math.hypot(px - line[0], py - line[1]));
    for (let i = 0; i + 3 < line.length; i += 2) {
      const d = pointSegmentDistance(px, py, line[i], line[i + 1], line[i + 2], line[i + 3]);
      if (d < best) best = d;
    }
  }
  return best;
}

/** sup over the points of `from` of their distance to `to` (the directed Hausdorff distance). */
export function directedHausdorff(from: readonly Polyline[], to: readonly Polyline[], step_mm = 0.05): number {
  const grid = new SegmentGrid(to);
  let worst = 0;
  for (const line of from) {
    for (let i = 0; i + 1 < line.length; i += 2) {
      worst = Math.max(worst, grid.distance(line[i], line[i + 1]));
      if (i + 3 >= line.length) break;
      const ax = line[i];
      const ay = line[i + 1];
      const dx = line[i + 2] - ax;
      const dy = line[i + 3] - ay;
      const n = Math.floor(Math.hypot(dx, dy) / step_mm);
      for (let k = 1; k < n; k++) worst = Math.max(worst, grid.distance(ax + (dx * k) / n, ay + (dy * k) / n));
    }
  }
  return worst;
}

export function hausdorff(a: readonly Polyline[], b: readonly Polyline[], step_mm = 0.05): number {
  return Math.max(directedHausdorff(a, b, step_mm), directedHausdorff(b, a, step_mm));
}
