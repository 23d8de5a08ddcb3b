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
 * ordering.property.test.ts. The nearest-end searches go through a grid of the
 * free ends (endpointGrid.ts), as vpype's go through a spatial index.
 */
import { EndpointGrid } from './endpointGrid.ts';
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
  let lines: Int32Array | null = null;
  if (a.lines || b.lines) {
    // As speeds; the gap's segment (when b does not touch) takes the line b starts at.
    lines = new Int32Array(n - 1);
    if (a.lines) lines.set(a.lines, 0);
    if (b.lines) {
      lines.set(b.lines, na - 1 + (touch ? 0 : 1));
      if (!touch) lines[na - 1] = b.lines[0] ?? 0;
    }
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
  return { points, speeds, dwells, lines };
}

/** x, y of each path's first point (end id 2i) and last point (2i + 1). */
function endsOf(paths: readonly PlotPath[]): Float64Array {
  const ends = new Float64Array(4 * paths.length);
  paths.forEach((p, i) => {
    const q = p.points;
    ends.set([q[0], q[1], q[q.length - 2], q[q.length - 1]], 4 * i);
  });
  return ends;
}

/**
 * Joins paths whose ends touch within `tolerance` mm. Paths are taken in order;
 * each grows at its end, then at its start, while a free path touches there.
 */
export function mergePaths(paths: readonly PlotPath[], tolerance: number): PlotPath[] {
  const grid = new EndpointGrid(endsOf(paths));
  const take = (i: number) => {
    grid.remove(2 * i);
    grid.remove(2 * i + 1);
  };
  const out: PlotPath[] = [];
  const used = new Uint8Array(paths.length);
  for (let i = 0; i < paths.length; i++) {
    if (used[i]) continue;
    used[i] = 1;
    take(i);
    let path = paths[i];
    for (;;) {
      const [x, y] = last(path);
      const end = grid.nearest(x, y, tolerance);
      if (end < 0) break;
      const j = end >> 1;
      used[j] = 1;
      take(j);
      // Its first point touches: drawn as it is; its last: drawn reversed.
      path = join(path, end & 1 ? reversed(paths[j]) : paths[j]);
    }
    for (;;) {
      const [x, y] = first(path);
      const end = grid.nearest(x, y, tolerance);
      if (end < 0) break;
      const j = end >> 1;
      used[j] = 1;
      take(j);
      // The other path ends here and goes first (reversed if it starts here).
      path = join(end & 1 ? paths[j] : reversed(paths[j]), path);
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
  const ends = endsOf(paths);
  const grid = new EndpointGrid(ends);
  const greedy: PlotPath[] = [];
  let x = start[0], y = start[1];
  for (let k = 0; k < paths.length; k++) {
    const end = grid.nearest(x, y);
    const j = end >> 1;
    grid.remove(2 * j);
    grid.remove(2 * j + 1);
    // Reached at its last point: drawn reversed, and left at its first.
    const flip = (end & 1) === 1;
    greedy.push(flip ? reversed(paths[j]) : paths[j]);
    const leave = flip ? 4 * j : 4 * j + 2;
    x = ends[leave];
    y = ends[leave + 1];
  }
  return travelLength(greedy, start) <= travelLength(paths, start) ? greedy : [...paths];
}
