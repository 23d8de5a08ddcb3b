/**
 * Timing: the path-length function s(t) of one segment, as a short list of
 * polynomial phases (docs/design.md, decision 1).
 *
 * Within phase k, with τ the time since the phase began:
 *   s(τ)  = s0 + v0·τ + a0·τ²/2 + j·τ³/6
 *   s′(τ) = v0 + a0·τ + j·τ²/2
 *   s″(τ) = a0 + j·τ
 * Trapezoidal profiles use j = 0 (constant acceleration). S-curve profiles only
 * need phases with j ≠ 0: nothing that evaluates phases has to change.
 *
 * Phases are contiguous: each starts where the previous one ended, in time, in
 * s and in s′. Units: s in mm, τ in seconds.
 */
/** One phase, as an object: the public view of a Timing. */
export interface Phase {
  /** s, time since the segment began at which this phase begins */
  t0: number;
  /** s */
  duration: number;
  /** mm, distance along the segment at the phase's start */
  s0: number;
  /** mm/s */
  v0: number;
  /** mm/s² */
  a0: number;
  /** mm/s³; 0 for trapezoidal profiles */
  jerk: number;
}

/**
 * A segment's phases packed flat, PHASE_STRIDE numbers per phase in the order of
 * Phase's fields: t0, duration, s0, v0, a0, jerk. One array of doubles instead of
 * an object per phase: the queue times a million segments a second.
 */
export type Timing = number[];
export const PHASE_STRIDE = 6;

export interface PathState {
  /** mm along the segment */
  s: number;
  /** mm/s */
  v: number;
  /** mm/s² */
  a: number;
}

export function phaseCount(timing: Timing): number {
  return timing.length / PHASE_STRIDE;
}

/** s, from the start of the first phase to the end of the last. */
export function timingDuration(timing: Timing): number {
  const o = timing.length - PHASE_STRIDE;
  return o < 0 ? 0 : timing[o] + timing[o + 1];
}

/** The phases as objects. */
export function phasesOf(timing: Timing): Phase[] {
  const phases: Phase[] = [];
  for (let o = 0; o < timing.length; o += PHASE_STRIDE) {
    phases.push({ t0: timing[o], duration: timing[o + 1], s0: timing[o + 2], v0: timing[o + 3], a0: timing[o + 4], jerk: timing[o + 5] });
  }
  return phases;
}

/** s, s′ and s″ at time t since the segment began; clamped to [0, duration]. */
export function evaluateTiming(timing: Timing, t: number, out: PathState): PathState {
  // The phase containing t (clamped to the first and last phase).
  let o = 0;
  while (o + PHASE_STRIDE < timing.length && t >= timing[o + PHASE_STRIDE]) o += PHASE_STRIDE;
  let tau = t - timing[o];
  const duration = timing[o + 1];
  if (tau < 0) tau = 0;
  if (tau > duration) tau = duration;
  const v0 = timing[o + 3];
  const a0 = timing[o + 4];
  const j = timing[o + 5];
  out.s = timing[o + 2] + tau * (v0 + tau * (a0 / 2 + (tau * j) / 6));
  out.v = v0 + tau * (a0 + (tau * j) / 2);
  out.a = a0 + tau * j;
  return out;
}

/**
 * The trapezoidal profile over a segment of length L (mm) entered at speed ve,
 * left at speed vx, with cruise speed at most vc and acceleration a.
 * Arguments are squared speeds, as the planner works in v².
 *
 * Accelerating from ve at a over distance d reaches v² = ve² + 2·a·d; decelerating
 * to vx over distance d starts from v² = vx² + 2·a·d. With a peak speed vp the
 * accelerating part takes d_acc = (vp² − ve²)/2a and the decelerating part
 * d_dec = (vp² − vx²)/2a. Both fit in L when
 *   (vp² − ve²)/2a + (vp² − vx²)/2a ≤ L  ⇔  vp² ≤ (2aL + ve² + vx²)/2,
 * so the peak is vp² = min(vc², (2aL + ve² + vx²)/2), and whatever distance is
 * left, L − d_acc − d_dec, is covered at vp. The planner guarantees
 * |vx² − ve²| ≤ 2aL, which makes vp ≥ max(ve, vx).
 *
 * Times: t_acc = (vp − ve)/a, t_dec = (vp − vx)/a, t_cruise = d_cruise/vp.
 * Phases of zero duration are left out.
 */
export function trapezoidTiming(length: number, entry2: number, exit2: number, cruise2: number, accel: number): Timing {
  const count = writeTrapezoid(scratch, 0, length, entry2, exit2, cruise2, accel);
  // Sized once rather than grown by push, which over-allocates (25 slots for 6) and would, were V8
  // to pretenure this allocation site, put young storage behind an old array (see ValidatedMove).
  const timing: Timing = new Array<number>(count * PHASE_STRIDE);
  for (let i = 0; i < timing.length; i++) timing[i] = scratch[i];
  return timing;
}

/** The most phases a trapezoid has: accelerate, cruise, decelerate. */
export const TRAPEZOID_MAX_PHASES = 3;

const scratch = new Float64Array(TRAPEZOID_MAX_PHASES * PHASE_STRIDE);

/**
 * timingDuration(trapezoidTiming(…)) without allocating: the same phases, so the
 * same duration to the last bit (the last phase's start plus its duration).
 */
export function trapezoidDuration(length: number, entry2: number, exit2: number, cruise2: number, accel: number): number {
  const o = (writeTrapezoid(scratch, 0, length, entry2, exit2, cruise2, accel) - 1) * PHASE_STRIDE;
  return scratch[o] + scratch[o + 1];
}

/**
 * Writes trapezoidTiming's phases into `out` from offset o and returns how many
 * there are (1 to 3): for planners that keep timings in columns, allocating nothing.
 */
export function writeTrapezoid(out: Float64Array, o: number, length: number, entry2: number, exit2: number, cruise2: number, accel: number): number {
  const p = scratchInputs;
  p.length = length;
  p.entry2 = entry2;
  p.exit2 = exit2;
  p.cruise2 = cruise2;
  p.accel = accel;
  return writeTrapezoidOf(out, o, p);
}

/** A line's trapezoid inputs (trapezoidTiming's arguments) as the fields of one object. */
export interface TrapezoidInputs {
  /** mm */
  length: number;
  /** Entry, exit and cruise speeds², mm²/s². */
  entry2: number;
  exit2: number;
  cruise2: number;
  /** mm/s² */
  accel: number;
}

/** writeTrapezoid's reused inputs. */
const scratchInputs: TrapezoidInputs = { length: 0.5, entry2: 0.5, exit2: 0.5, cruise2: 0.5, accel: 0.5 };

/**
 * writeTrapezoid with its inputs read from an object the caller reuses, for the
 * queue's executor, which times a million lines a second: a number passed as an
 * argument to a call the engine does not inline is allocated on the heap, one read
 * from a field is not. The same arithmetic, so the same phases to the last bit.
 */
export function writeTrapezoidOf(out: Float64Array, o: number, p: TrapezoidInputs): number {
  const length = p.length;
  const entry2 = p.entry2;
  const exit2 = p.exit2;
  const cruise2 = p.cruise2;
  const accel = p.accel;
  const ve = Math.sqrt(entry2);
  const vx = Math.sqrt(exit2);
  let vp2 = Math.min(cruise2, (2 * accel * length + entry2 + exit2) / 2);
  // Rounding can leave vp² a hair below ve² or vx²; the profile must not dip.
  vp2 = Math.max(vp2, entry2, exit2);
  const vp = Math.sqrt(vp2);
  const dAcc = (vp2 - entry2) / (2 * accel);
  const dDec = (vp2 - exit2) / (2 * accel);
  const dCruise = Math.max(0, length - dAcc - dDec);

  const tAcc = (vp - ve) / accel;
  const cruises = dCruise > 0 && vp > 0;
  const tDec = (vp - vx) / accel;
  const count = (tAcc > 0 ? 1 : 0) + (cruises ? 1 : 0) + (tDec > 0 ? 1 : 0);
  // Only a segment of zero length and zero speed has no phase; the queue skips those.
  if (count === 0) {
    writePhase(out, o, 0, 0, 0, ve, 0);
    return 1;
  }
  let t = 0;
  let s = 0;
  if (tAcc > 0) {
    o = writePhase(out, o, t, tAcc, s, ve, accel);
    t += tAcc;
    s += dAcc;
  }
  if (cruises) {
    const tCruise = dCruise / vp;
    o = writePhase(out, o, t, tCruise, s, vp, 0);
    t += tCruise;
    s += dCruise;
  }
  if (tDec > 0) writePhase(out, o, t, tDec, s, vp, -accel);
  return count;
}

/**
 * A dwell's timing: one phase at rest, s(τ) = 0 with s′ = s″ = 0, lasting
 * `seconds` (0 for an event-only move: the phase is an instant).
 */
export function dwellTiming(seconds: number): Timing {
  return [0, seconds, 0, 0, 0, 0];
}

/** Writes a constant-acceleration phase at offset o; returns the offset after it. */
function writePhase(timing: Float64Array, o: number, t0: number, duration: number, s0: number, v0: number, a0: number): number {
  timing[o] = t0;
  timing[o + 1] = duration;
  timing[o + 2] = s0;
  timing[o + 3] = v0;
  timing[o + 4] = a0;
  timing[o + 5] = 0;
  return o + PHASE_STRIDE;
}
