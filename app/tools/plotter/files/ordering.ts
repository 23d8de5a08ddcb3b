/**
 * Cutting pen-up travel, as vpype's `linemerge` and `linesort` do.
 *
 * - mergePaths: a path whose end touches another's start or end (within a
 *   tolerance) is joined to it, reversing the other when needed, so the pen stays
 *   down across the join. A gap of at most the tolerance is drawn as one short
 *   pen-down segment (an exact touch adds none).
 * - sortPaths: greedy nearest neighbour from the pen's position. At each step the
 *   pen goes to the closest free end of any path, and a path whose nearer end is
 *   its last point is drawn reversed. Greedy nearest neighbour is not guaranteed to
 *   beat every order (a file's own order may already be better), so the result
 *   is the shorter of the two: the travel is never longer than the file's order.
 *
 * Both keep every segment of the drawing (as an unordered pair of points); see
 * ordering.property.test.ts. The nearest-end search is a scan, O(n²) over n paths:
 * a few thousand paths take milliseconds in the worker; vpype uses a spatial
 * index for its larger drawings.
 */
import { pointCount, reversed, travelLength, type PlotPath } from './paths.ts';

/** mm: the default join tolerance (vpype's linemerge default is 0.05 mm). */
export const DEFAULT_MERGE_TOLERANCE_MM = 0.05;

function first(p: PlotPath): [number, number] {
  return [p.points[0], p.points[1]];
}

function last(p: PlotPath): [number, number] {
  const n = p.points.length;
  return [p.points[n - 2], p.points[n - 1]];
}

/** b drawn right after a, the pen down across the join. */
function join(a: PlotPath, b: PlotPath): PlotPath {
  const [ax, ay] = last(a);
  const touch = b.points[0] === ax && b.points[1] === ay;
  const bFrom = touch ? 1 : 0;
  const na = pointCount(a), nb = pointCount(b);
  const n = na + nb - bFrom;
  const points = new Float64Array(2 * n);
  points.set(a.points, 0);
  points.set(b.points.subarray(2 * bFrom), 2 * na);
  let speeds: Float64Array | null = null;
  if (a.speeds || b.speeds) {
    // Segments: a's (na − 1), the gap's (when b does not touch: at the pen-down setting, 0), b's (nb − 1).
    speeds = new Float64Array(n - 1);
    if (a.speeds) speeds.set(a.speeds, 0);
    if (b.speeds) speeds.set(b.speeds, na - 1 + (touch ? 0 : 1));
  }
  let dwells: Float64Array | null = null;
  if (a.dwells || b.dwells) {
    dwells = new Float64Array(n);
    if (a.dwells) dwells.set(a.dwells, 0);
    if (b.dwells) {
      // b's point k lands at off + k; when b touches, its first point is a's last.
      const off = touch ? na - 1 : na;
      for (let k = 0; k < nb; k++) dwells[off + k] += b.dwells[k];
    }
  }
  return { points, speeds, dwells };
}

/**
 * Joins paths whose ends touch within `tolerance` mm. Paths are taken in order;
 * each grows at its end, then at its start, while a free path touches there.
 */
export function mergePaths(paths: readonly PlotPath[], tolerance: number): PlotPath[] {
  const used = new Uint8Array(paths.length);
  const out: PlotPath[] = [];
  const tol2 = tolerance * tolerance;
  /** The free path with an end within the tolerance of (x, y): its index and whether it must be reversed to start there. */
  const touching = (x: number, y: number): [number, boolean] | null => {
    let best = -1, bestD2 = Infinity, flip = false;
    for (let j = 0; j < paths.length; j++) {
      if (used[j]) continue;
      const p = paths[j].points;
      const d0 = (p[0] - x) ** 2 + (p[1] - y) ** 2;
      const d1 = (p[p.length - 2] - x) ** 2 + (p[p.length - 1] - y) ** 2;
      if (d0 <= tol2 && d0 < bestD2) [best, bestD2, flip] = [j, d0, false];
      if (d1 <= tol2 && d1 < bestD2) [best, bestD2, flip] = [j, d1, true];
    }
    return best >= 0 ? [best, flip] : null;
  };
  for (let i = 0; i < paths.length; i++) {
    if (used[i]) continue;
    used[i] = 1;
    let path = paths[i];
    for (;;) {
      const [x, y] = last(path);
      const t = touching(x, y);
      if (!t) break;
      used[t[0]] = 1;
      path = join(path, t[1] ? reversed(paths[t[0]]) : paths[t[0]]);
    }
    for (;;) {
      const [x, y] = first(path);
      const t = touching(x, y);
      if (!t) break;
      used[t[0]] = 1;
      // The other path ends here: it goes first (reversed if it starts here).
      path = join(t[1] ? paths[t[0]] : reversed(paths[t[0]]), path);
    }
    out.push(path);
  }
  return out;
}

/**
 * Orders the paths (reversing some) to cut pen-up travel from `start`: greedy
 * nearest neighbour, or the file's order if that is no longer.
 */
export function sortPaths(paths: readonly PlotPath[], start: readonly [number, number]): PlotPath[] {
  const n = paths.length;
  const ends = new Float64Array(4 * n);
  for (let i = 0; i < n; i++) {
    const p = paths[i].points;
    ends.set([p[0], p[1], p[p.length - 2], p[p.length - 1]], 4 * i);
  }
  const used = new Uint8Array(n);
  const greedy: PlotPath[] = [];
  let x = start[0], y = start[1];
  for (let k = 0; k < n; k++) {
    let best = -1, bestD2 = Infinity, flip = false;
    for (let j = 0; j < n; j++) {
      if (used[j]) continue;
      const d0 = (ends[4 * j] - x) ** 2 + (ends[4 * j + 1] - y) ** 2;
      const d1 = (ends[4 * j + 2] - x) ** 2 + (ends[4 * j + 3] - y) ** 2;
      if (d0 < bestD2) [best, bestD2, flip] = [j, d0, false];
      if (d1 < bestD2) [best, bestD2, flip] = [j, d1, true];
    }
    used[best] = 1;
    const p = flip ? reversed(paths[best]) : paths[best];
    greedy.push(p);
    x = flip ? ends[4 * best] : ends[4 * best + 2];
    y = flip ? ends[4 * best + 1] : ends[4 * best + 3];
  }
  return travelLength(greedy, start) <= travelLength(paths, start) ? greedy : [...paths];
}
