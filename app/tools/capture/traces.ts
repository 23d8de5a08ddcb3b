/**
 * A record's curves for the plots, in seconds from the capture's start: the planned
 * acceleration per axis, and a sensor channel with a break (a NaN point) at every gap,
 * so a line never joins across lost samples.
 */
import type { CaptureRecord } from './protocol.ts';

export interface Point {
  t: number;
  v: number;
}

export function plannedCurve(record: CaptureRecord, axis: number): Point[] {
  const t = record.plan.t_us;
  const a = record.plan.acceleration[axis];
  return Array.from(t, (x, j) => ({ t: (x - record.start_us) / 1e6, v: a[j] }));
}

export function measuredCurve(record: CaptureRecord, sensor: number, channel: number): Point[] {
  const trace = record.sensors[sensor];
  if (!trace) return [];
  const breaks = new Set(trace.gaps.filter((g) => g.kind === 'lost').map((g) => g.index));
  const out: Point[] = [];
  const values = trace.values[channel];
  for (let k = 0; k < trace.author_us.length; k++) {
    const t = (trace.author_us[k] - record.start_us) / 1e6;
    if (breaks.has(k)) out.push({ t, v: NaN });
    out.push({ t, v: values[k] });
  }
  return out;
}

/** The index of the point nearest t in a time-ordered curve (ignoring breaks), or −1. */
export function nearest(points: readonly Point[], t: number): number {
  let lo = 0;
  let hi = points.length - 1;
  if (hi < 0) return -1;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (points[mid].t < t) lo = mid + 1;
    else hi = mid;
  }
  let best = lo;
  if (lo > 0 && Math.abs(points[lo - 1].t - t) < Math.abs(points[lo].t - t)) best = lo - 1;
  if (Number.isNaN(points[best].v)) best = best + 1 < points.length ? best + 1 : best - 1;
  return best >= 0 && !Number.isNaN(points[best].v) ? best : -1;
}
