/**
 * The draw bench's figures (definitions in bench/draw.ts) from what the simulator
 * saw: the pointer's points on the author's clock and the pen's ink with its times.
 */
import { hausdorff, pointDrawingDistance } from '../app/tools/plotter/geometry/hausdorff.ts';
import { DistanceThinner } from '../app/tools/plotter/live/thinning.ts';
import type { DrawTruth } from '../app/tools/plotter/protocol.ts';
import type { StrokeSpec } from './drawStrokes.ts';


/** Where on ink segment i (from sample i to i + 1) the point (x, y) is nearest: [fraction, distance]. */
function nearestOn(ink: number[], i: number, x: number, y: number): [number, number] {
  const ax = ink[3 * i];
  const ay = ink[3 * i + 1];
  const dx = ink[3 * i + 3] - ax;
  const dy = ink[3 * i + 4] - ay;
  const l2 = dx * dx + dy * dy;
  const f = l2 > 0 ? Math.max(0, Math.min(1, ((x - ax) * dx + (y - ay) * dy) / l2)) : 0;
  return [f, Math.hypot(x - (ax + f * dx), y - (ay + f * dy))];
}

/** The pen adds an ink sample only when the tool moved this far (core/sim/presets/blotPlotter.ts): distances this close are one pass. */
const SAMPLE_MIN_MM = 0.01;

/**
 * Author µs at which the ink passes (x, y), searching forward from sample `from`:
 * the earliest moment the ink comes within SAMPLE_MIN_MM of its nearest approach
 * (interpolated along the segment between two 1 ms samples). Earliest, not nearest:
 * a tool that comes to rest on the point (a stroke's end, while the pen lifts)
 * stays at the nearest distance for a while. Also returns that sample.
 */
function passTime(ink: number[], x: number, y: number, from: number): { t: number; i: number; d: number } {
  let best = Infinity;
  // The tool passes each point once, in order: look a little ahead of the last match only (≤ 20 mm of ink).
  let walked = 0;
  let end = from;
  for (let i = from; i + 1 < ink.length / 3; i++) {
    best = Math.min(best, nearestOn(ink, i, x, y)[1]);
    end = i;
    walked += Math.hypot(ink[3 * i + 3] - ink[3 * i], ink[3 * i + 4] - ink[3 * i + 1]);
    if (walked > 20 && best < 0.5) break;
  }
  for (let i = from; i <= end; i++) {
    const [f, d] = nearestOn(ink, i, x, y);
    if (d <= best + SAMPLE_MIN_MM) {
      const t = ink[3 * i + 2] + f * (ink[3 * i + 5] - ink[3 * i + 2]);
      return { t, i, d };
    }
  }
  return { t: ink[3 * from + 2], i: from, d: best };
}

/** The pointer's largest gap between point stamps, and its slowest arrival, in the `window_us` before author time `t`. */
function inputBefore(stroke: { points: number[]; arrived: number[] }, t: number, window_us: number): { inputGapMs: number; arrivalMaxMs: number } {
  let gap = 0;
  let arrival = 0;
  for (let j = 1; j < stroke.points.length / 3; j++) {
    const stamp = stroke.points[3 * j + 2];
    if (stamp < t - window_us || stamp > t) continue;
    gap = Math.max(gap, stamp - stroke.points[3 * j - 1]);
    arrival = Math.max(arrival, stroke.arrived[j] - stamp);
  }
  return { inputGapMs: round(gap / 1000), arrivalMaxMs: round(arrival / 1000) };
}

export function percentile(sorted: number[], q: number): number {
  if (sorted.length === 0) return NaN;
  return sorted[Math.min(sorted.length - 1, Math.max(0, Math.ceil(q * sorted.length) - 1))];
}

export const round = (v: number, d = 1) => Math.round(v * 10 ** d) / 10 ** d;

/**
 * Every figure, for strokes drawn in the order of `specs`; `fastSent` is how many
 * points the pointer sent for the fast stroke.
 */
export function drawFigures(truth: Pick<DrawTruth, 'ink' | 'strokes' | 'lead_us' | 'limits' | 'tolerance_mm'>, specs: readonly StrokeSpec[], fastSent: number) {
  const smoothSpeed = specs.find((s) => s.kind === 'smooth')?.speed ?? NaN;
  const lags: number[] = [];
  /** ms from a pointer event to the worker's drawer taking its point, on the author's clock (never negative: see app/tools/plotter/live/pointerTimeline.ts). */
  const arrivals: number[] = [];
  let stops = 0;
  /** For each rest inside a curve: when, and the pointer's largest gap and slowest arrival in the 100 ms before it. */
  const stopCauses: Array<{ stroke: string; atMs: number; inputGapMs: number; arrivalMaxMs: number }> = [];
  const kept: number[] = [];
  for (const [k, spec] of specs.entries()) {
    if (spec.kind !== 'smooth') continue;
    const pts = truth.strokes[k].points;
    const ink = truth.ink[k];
    let from = 0;
    const passes: number[] = [];
    for (let j = 0; j < pts.length / 3; j++) {
      const p = passTime(ink, pts[3 * j], pts[3 * j + 1], from);
      from = p.i;
      passes.push(p.t);
      if (j > 0) lags.push((p.t - pts[3 * j + 2]) / 1000);
      arrivals.push((truth.strokes[k].arrived[j] - pts[3 * j + 2]) / 1000);
    }
    // Rest inside the curve: a gap in the ink samples between the second point's pass and the second-to-last's.
    const tA = passes[1];
    const tB = passes[passes.length - 2];
    for (let i = 1; i < ink.length / 3; i++) {
      const t = ink[3 * i + 2];
      if (t > tA && t < tB && t - ink[3 * i - 1] > 5000) {
        stops++;
        stopCauses.push({ stroke: spec.name, atMs: round((ink[3 * i - 1] - pts[2]) / 1000), ...inputBefore(truth.strokes[k], ink[3 * i - 1], 100_000) });
      }
    }
    // The pointer's sampling interval after thinning.
    const thinner = new DistanceThinner(truth.tolerance_mm);
    let lastKept = NaN;
    for (let j = 0; j < pts.length / 3; j++) {
      if (!thinner.push([pts[3 * j], pts[3 * j + 1]])) continue;
      const t = pts[3 * j + 2];
      if (Number.isFinite(lastKept)) kept.push((t - lastKept) / 1000);
      lastKept = t;
    }
  }
  lags.sort((a, b) => a - b);
  arrivals.sort((a, b) => a - b);
  const sampling = kept.reduce((a, b) => a + b, 0) / kept.length;
  const brakeMs = (smoothSpeed / (2 * truth.limits.maxAcceleration)) * 1000;
  const leadMs = truth.lead_us / 1000;
  const lagFloorMs = brakeMs + leadMs + sampling;

  const strokesMm = truth.strokes.map((s) => s.points.filter((_, i) => i % 3 !== 2));
  const inkMm = truth.ink.map((s) => s.filter((_, i) => i % 3 !== 2));
  const inkErrorMm = hausdorff(strokesMm, inkMm);

  const fastIndex = specs.findIndex((s) => s.kind === 'fast');
  const fast = truth.strokes[fastIndex];
  let fastOff = 0;
  for (let j = 0; j < fast.points.length / 3; j++) if (pointDrawingDistance(fast.points[3 * j], fast.points[3 * j + 1], [inkMm[fastIndex]]) > 0.3) fastOff++;
  const pointsDropped = fastSent - fast.points.length / 3 + fastOff;

  return {
    toolLagMs: { p50: round(percentile(lags, 0.5)), p99: round(percentile(lags, 0.99)), max: round(lags.at(-1) ?? NaN) },
    lagFloorMs: round(lagFloorMs),
    lagFloorTerms: { brakeMs_v_over_2a: round(brakeMs), leadMs_streamer: round(leadMs), samplingMs_pointer_after_thinning: round(sampling) },
    lagPoints: lags.length,
    stopsInsideStrokes: stops,
    stopCauses,
    inkErrorMm: round(inkErrorMm, 3),
    pointsDropped,
    fastStroke: { pointsSent: fastSent, pointsReceived: fast.points.length / 3, behindMaxMm: round(fast.behindMax_mm), waitingMax: fast.waitingMax },
    pointArrivalMs: { min: round(arrivals[0]), p50: round(percentile(arrivals, 0.5)), max: round(arrivals.at(-1) ?? NaN) },
    strokes: specs.map((s, k) => ({ name: s.name, speed: s.speed, points: truth.strokes[k].points.length / 3, inkPoints: truth.ink[k].length / 3 })),
    targets: { toolLagP99MaxMs: round(lagFloorMs + 5), stopsInsideStrokes: 0, inkErrorMm: 0.3, pointsDropped: 0 },
    pass: {
      toolLag: percentile(lags, 0.99) <= lagFloorMs + 5,
      stops: stops === 0,
      ink: inkErrorMm <= 0.3,
      dropped: pointsDropped === 0,
    },
  };
}
