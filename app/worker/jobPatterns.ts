/**
 * Jobs drawn in the worker: a square, a spiral and a zigzag raster of any number of
 * segments, from the work origin, within `size` mm. Machines with one motion axis
 * get the pattern's x; with three or more, the other axes stay where the origin is.
 */
import type { JobPattern } from './protocol.ts';

/** n × axes points, row-major. */
export function patternPoints(pattern: JobPattern, segments: number, size: number, origin: readonly number[]): Float64Array {
  const axes = origin.length;
  const n = pattern === 'square' ? 4 : Math.max(1, Math.floor(segments));
  const out = new Float64Array(n * axes);
  const put = (i: number, x: number, y: number) => {
    const o = i * axes;
    for (let a = 0; a < axes; a++) out[o + a] = origin[a];
    out[o] += x;
    if (axes > 1) out[o + 1] += y;
  };
  if (pattern === 'square') {
    put(0, size, 0);
    put(1, size, size);
    put(2, 0, size);
    put(3, 0, 0);
  } else if (pattern === 'spiral') {
    // An Archimedean spiral r = bθ from the centre out, about 64 points per turn at
    // most, in steps of equal length: the arc length from the centre is about bθ²/2,
    // so point i sits at θ = θmax·√((i + 1)/n).
    const turns = Math.max(1, Math.min(200, n / 64));
    const r = size / 2;
    const thetaMax = turns * 2 * Math.PI;
    for (let i = 0; i < n; i++) {
      const theta = thetaMax * Math.sqrt((i + 1) / n);
      const radius = (r * theta) / thetaMax;
      put(i, r + radius * Math.cos(theta), r + radius * Math.sin(theta));
    }
  } else {
    // A raster: rows along x, stepping in y; each row is split into equal segments.
    const rows = Math.max(1, Math.round(Math.sqrt(n / 8)));
    const perRow = Math.max(1, Math.ceil(n / rows) - 1);
    let i = 0;
    for (let row = 0; row < rows && i < n; row++) {
      const y = rows === 1 ? 0 : (size * row) / (rows - 1);
      const forward = row % 2 === 0;
      if (row > 0 && i < n) put(i++, forward ? 0 : size, y);
      for (let k = 1; k <= perRow && i < n; k++) put(i++, size * (forward ? k / perRow : 1 - k / perRow), y);
    }
    return out.subarray(0, i * axes);
  }
  return out;
}
