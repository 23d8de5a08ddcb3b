/**
 * What a time plot of many samples draws: per pixel column, the first, lowest, highest
 * and last sample in it (the "M4" reduction of Jugel et al., VLDB 2014; oscilloscopes
 * and Klipper's motan graphs do the same min/max per column).
 *
 * Why it looks the same as drawing every sample: a line drawn through the samples of one
 * column covers, in that column, every height between their minimum and maximum (it is
 * continuous), and it enters the column at the first sample and leaves at the last. So
 * the polyline first → min → max → last (in their own order) covers the same pixels in
 * that column, and joins the neighbouring columns at the same points. The line drawn
 * then has at most 4 points a column: its cost follows the plot's width, not the
 * number of samples (a 10-minute capture at 1 kHz is 600 000 samples over ~700 columns).
 *
 * Breaks: the line never joins across lost samples, nor over a value that is not a
 * number (the plan before the history's horizon). A break closes the column's group
 * and starts another, so min/max are per (column, unbroken run), and the output marks
 * each break with −1.
 *
 * Only the samples in [t0, t1] and one neighbour each side (so the line runs off the
 * plot's edges) are read: zoomed in, the work follows the samples in view. Finding
 * them is a binary search.
 */

export interface Curve {
  /** each sample's time, ascending */
  t: ArrayLike<number>;
  /** each sample's value (NaN: unknown, the line breaks there) */
  v: ArrayLike<number>;
  /** ascending indices k where samples were lost between k − 1 and k */
  breaks: ArrayLike<number>;
}

export interface Decimated {
  /** indices of the samples to draw, in order; −1 marks a break in the line */
  index: Int32Array;
  /** samples with t in [t0, t1] */
  samplesInView: number;
  /** first and last index read (the view and one neighbour each side); lo > hi when none */
  lo: number;
  hi: number;
}

/** The first index with t[k] ≥ x (t ascending), or t.length. */
export function lowerBound(t: ArrayLike<number>, x: number): number {
  let lo = 0;
  let hi = t.length;
  while (lo < hi) {
    const mid = (lo + hi) >>> 1;
    if (t[mid] < x) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

/** The first index with t[k] > x, or t.length. */
export function upperBound(t: ArrayLike<number>, x: number): number {
  let lo = 0;
  let hi = t.length;
  while (lo < hi) {
    const mid = (lo + hi) >>> 1;
    if (t[mid] <= x) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

/**
 * The column of time x for `columns` columns over [t0, t1]: 0 … columns − 1 inside,
 * −1 before and `columns` after (the neighbours outside get columns of their own).
 */
export function columnOf(x: number, t0: number, t1: number, columns: number): number {
  if (x < t0) return -1;
  if (x > t1) return columns;
  const width = (t1 - t0) / columns;
  return width > 0 ? Math.min(columns - 1, Math.floor((x - t0) / width)) : 0;
}

export function decimateMinMax(curve: Curve, t0: number, t1: number, columns: number): Decimated {
  const { t, v, breaks } = curve;
  const n = Math.min(t.length, v.length);
  const cols = Math.max(1, Math.floor(columns));
  const first = lowerBound(t, t0);
  const end = Math.min(n, upperBound(t, t1));
  const lo = Math.max(0, first - 1);
  const hi = Math.min(n - 1, end);
  const out: number[] = [];
  let nextBreak = lowerBound(breaks, lo + 1);
  // The open group: its column and its first, lowest, highest and last samples.
  let column = NaN;
  let gFirst = -1;
  let gMin = -1;
  let gMax = -1;
  let gLast = -1;
  const flush = () => {
    if (gFirst < 0) return;
    // The four in index order, each once.
    const picks = [gFirst, gMin, gMax, gLast].sort((a, b) => a - b);
    for (let i = 0; i < 4; i++) if (i === 0 || picks[i] !== picks[i - 1]) out.push(picks[i]);
    gFirst = -1;
  };
  const breakLine = () => {
    flush();
    if (out.length > 0 && out[out.length - 1] !== -1) out.push(-1);
  };
  for (let k = lo; k <= hi; k++) {
    if (nextBreak < breaks.length && breaks[nextBreak] === k) {
      breakLine();
      nextBreak++;
    }
    const value = v[k];
    if (!Number.isFinite(value)) {
      breakLine();
      continue;
    }
    const c = columnOf(t[k], t0, t1, cols);
    if (gFirst >= 0 && c === column) {
      if (value < v[gMin]) gMin = k;
      if (value > v[gMax]) gMax = k;
      gLast = k;
      continue;
    }
    flush();
    column = c;
    gFirst = gMin = gMax = gLast = k;
  }
  flush();
  if (out.length > 0 && out[out.length - 1] === -1) out.pop();
  return { index: Int32Array.from(out), samplesInView: Math.max(0, end - first), lo, hi };
}
