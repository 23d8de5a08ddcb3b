/**
 * A coarse copy of a job's path for the overview: consecutive points closer than
 * `tolerance` mm to the last point kept are dropped (radial distance), so the
 * copy stays within `tolerance` of the path. The view draws it while one
 * millimetre covers too few pixels for the difference to show, and the full path
 * when zoomed in.
 */
export interface Decimated {
  vertices: Float32Array;
  /** For each vertex kept, the index of the full path's vertex it is. */
  index: Uint32Array;
}

export function decimate(vertices: Float32Array, tolerance: number): Decimated {
  const n = vertices.length / 3;
  const keep = new Uint32Array(n);
  let kept = 0;
  const t2 = tolerance * tolerance;
  let lx = NaN, ly = NaN, lz = NaN;
  for (let i = 0; i < n; i++) {
    const x = vertices[i * 3], y = vertices[i * 3 + 1], z = vertices[i * 3 + 2];
    const dx = x - lx, dy = y - ly, dz = z - lz;
    if (i === 0 || i === n - 1 || !(dx * dx + dy * dy + dz * dz < t2)) {
      keep[kept++] = i;
      lx = x;
      ly = y;
      lz = z;
    }
  }
  const out = new Float32Array(kept * 3);
  for (let k = 0; k < kept; k++) out.set(vertices.subarray(keep[k] * 3, keep[k] * 3 + 3), k * 3);
  return { vertices: out, index: keep.slice(0, kept) };
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
