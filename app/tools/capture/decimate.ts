/**
 * Fewer points for a plot without losing its peaks: the series is cut into `points`
 * buckets and each keeps its largest value (at that value's own x), so a peak one bin
 * wide survives any decimation. For spectra, where the peak is what matters.
 */
export function decimateMax(values: ArrayLike<number>, step: number, points: number): { x: Float64Array; y: Float64Array } {
  const n = values.length;
  const buckets = Math.min(n, Math.max(1, Math.floor(points)));
  const x = new Float64Array(buckets);
  const y = new Float64Array(buckets);
  for (let b = 0; b < buckets; b++) {
    const lo = Math.floor((b * n) / buckets);
    const hi = Math.floor(((b + 1) * n) / buckets);
    let best = lo;
    for (let k = lo + 1; k < hi; k++) if (values[k] > values[best]) best = k;
    x[b] = best * step;
    y[b] = values[best];
  }
  return { x, y };
}
