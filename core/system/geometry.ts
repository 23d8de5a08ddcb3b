/** Distance (mm) from a point to a polyline. */
export function distanceToPolyline(p: readonly number[], points: readonly (readonly number[])[]): number {
  let best = Infinity;
  for (let k = 1; k < points.length; k++) {
    const a = points[k - 1];
    const b = points[k];
    const ab = a.map((v, i) => b[i] - v);
    const len2 = ab.reduce((s, v) => s + v * v, 0);
    const t = len2 === 0 ? 0 : Math.max(0, Math.min(1, ab.reduce((s, v, i) => s + v * (p[i] - a[i]), 0) / len2));
    const d = Math.hypot(...a.map((v, i) => v + t * ab[i] - p[i]));
    best = Math.min(best, d);
  }
  return best;
}

/**
 * The Blot-sized test path the stop and recovery tests share: long straights and
 * corners, fast enough that braking takes a while (mm).
 */
export function corneredPath(): number[][] {
  return [
    [10, 10],
    [90, 10],
    [90, 60],
    [30, 70],
    [30, 20],
    [80, 40],
  ];
}
