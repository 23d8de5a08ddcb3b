/**
 * A coarse copy of a job's path for the overview: the Douglas–Peucker
 * simplification of the polyline, which keeps a subset of its vertices such that
 * every vertex dropped lies within `tolerance` mm of the kept chord spanning it.
 * So the copy stays within `tolerance` of the path, and a smooth curve of short
 * moves (a fine spiral: 0.5 mm chords, where a chord within 0.1 mm can be ~6 mm
 * long) shrinks many times over. The view draws it while one millimetre covers too
 * few pixels for the difference to show, and the full path when zoomed in.
 *
 * Iterative (an explicit stack, no recursion depth limit), and run on stretches
 * of CHUNK vertices whose ends are always kept: a path that winds round and round
 * (a spiral) otherwise splits one vertex at a time off long chords, O(n²). Chunks
 * bound the work at O(n·CHUNK) and cost one kept vertex per CHUNK.
 */
const CHUNK = 1024;

export interface Decimated {
  vertices: Float32Array;
  /** For each vertex kept, the index of the full path's vertex it is (ascending). */
  index: Uint32Array;
}

export function decimate(vertices: Float32Array, tolerance: number): Decimated {
  const n = vertices.length / 3;
  if (n <= 2) return { vertices: vertices.slice(), index: Uint32Array.from({ length: n }, (_, i) => i) };
  const keep = new Uint8Array(n);
  keep[0] = 1;
  keep[n - 1] = 1;
  const t2 = tolerance * tolerance;
  const stack: number[] = [];
  for (let a = 0; a < n - 1; a += CHUNK) {
    const b = Math.min(n - 1, a + CHUNK);
    keep[b] = 1;
    stack.push(a, b);
  }
  while (stack.length > 0) {
    const last = stack.pop() as number;
    const first = stack.pop() as number;
    // The vertex farthest from the chord first→last (distance to the segment, in 3D).
    const ax = vertices[first * 3], ay = vertices[first * 3 + 1], az = vertices[first * 3 + 2];
    const dx = vertices[last * 3] - ax, dy = vertices[last * 3 + 1] - ay, dz = vertices[last * 3 + 2] - az;
    const len2 = dx * dx + dy * dy + dz * dz;
    let worst = -1;
    let worstD2 = t2;
    for (let i = first + 1; i < last; i++) {
      const px = vertices[i * 3] - ax, py = vertices[i * 3 + 1] - ay, pz = vertices[i * 3 + 2] - az;
      let u = len2 > 0 ? (px * dx + py * dy + pz * dz) / len2 : 0;
      u = u < 0 ? 0 : u > 1 ? 1 : u;
      const ex = px - u * dx, ey = py - u * dy, ez = pz - u * dz;
      const d2 = ex * ex + ey * ey + ez * ez;
      if (d2 > worstD2) {
        worstD2 = d2;
        worst = i;
      }
    }
    if (worst >= 0) {
      keep[worst] = 1;
      stack.push(first, worst, worst, last);
    }
  }
  let kept = 0;
  for (let i = 0; i < n; i++) kept += keep[i];
  const out = new Float32Array(kept * 3);
  const index = new Uint32Array(kept);
  for (let i = 0, k = 0; i < n; i++) {
    if (!keep[i]) continue;
    index[k] = i;
    out[k * 3] = vertices[i * 3];
    out[k * 3 + 1] = vertices[i * 3 + 1];
    out[k * 3 + 2] = vertices[i * 3 + 2];
    k++;
  }
  return { vertices: out, index };
}

/** mm: a fraction of the path's extent, well under a pixel when the whole path fills the view. */
export function overviewTolerance(vertices: Float32Array): number {
  let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity;
  for (let i = 0; i < vertices.length; i += 3) {
    const x = vertices[i], y = vertices[i + 1];
    if (x < minX) minX = x;
    if (x > maxX) maxX = x;
    if (y < minY) minY = y;
    if (y > maxY) maxY = y;
  }
  return Math.max(maxX - minX, maxY - minY, 1) / 1500;
}
