/**
 * A record's curves for the plots, in seconds from the capture's start, as columns
 * (no per-sample objects): the planned acceleration per axis, and a sensor channel
 * with a break at every gap, so a line never joins across lost samples
 * (minMaxDecimation.ts draws them).
 */
import type { Curve } from './minMaxDecimation.ts';
import type { CaptureRecord } from './protocol.ts';

/** Author µs to seconds from `start_us`, in one new column. */
function secondsFrom(times_us: ArrayLike<number>, start_us: number): Float64Array {
  const out = new Float64Array(times_us.length);
  for (let k = 0; k < out.length; k++) out[k] = (times_us[k] - start_us) / 1e6;
  return out;
}

export function plannedCurve(record: CaptureRecord, axis: number): Curve {
  return { t: secondsFrom(record.plan.t_us, record.start_us), v: record.plan.acceleration[axis] ?? new Float64Array(0), breaks: new Int32Array(0) };
}

export function measuredCurve(record: CaptureRecord, sensor: number, channel: number): Curve {
  const trace = record.sensors[sensor];
  if (!trace) return { t: new Float64Array(0), v: new Float64Array(0), breaks: new Int32Array(0) };
  const breaks = Int32Array.from(new Set(trace.gaps.filter((g) => g.kind === 'lost').map((g) => g.index))).sort();
  return { t: secondsFrom(trace.author_us, record.start_us), v: trace.values[channel], breaks };
}

/** The index of the sample nearest t in a time-ordered curve with a known value, or −1. */
export function nearest(curve: Curve, t: number): number {
  const { t: times, v } = curve;
  const n = Math.min(times.length, v.length);
  if (n === 0) return -1;
  let lo = 0;
  let hi = n - 1;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (times[mid] < t) lo = mid + 1;
    else hi = mid;
  }
  // The nearer of the two around t, then outwards to the nearest with a value.
  const best = lo > 0 && Math.abs(times[lo - 1] - t) < Math.abs(times[lo] - t) ? lo - 1 : lo;
  for (let step = 0; step < n; step++) {
    const before = best - step;
    const after = best + step;
    const candidates = [before, after].filter((k) => k >= 0 && k < n && Number.isFinite(v[k]));
    if (candidates.length > 0) return candidates.reduce((a, b) => (Math.abs(times[b] - t) < Math.abs(times[a] - t) ? b : a));
    if (before < 0 && after >= n) break;
  }
  return -1;
}
