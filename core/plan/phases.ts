/**
 * Timing: the path-length function s(t) of one segment, as a short list of
 * polynomial phases (DESIGN.md decision 1).
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

export interface PathState {
  /** mm along the segment */
  s: number;
  /** mm/s */
  v: number;
  /** mm/s² */
  a: number;
}

/** Index of the phase containing time t (clamped to the first and last phase). */
export function phaseIndexAt(phases: readonly Phase[], t: number): number {
  let k = 0;
  while (k + 1 < phases.length && t >= phases[k + 1].t0) k++;
  return k;
}

/** s, s′ and s″ at time t since the segment began; clamped to [0, duration]. */
export function evaluatePhases(phases: readonly Phase[], t: number, out: PathState): PathState {
  const p = phases[phaseIndexAt(phases, t)];
  let tau = t - p.t0;
  if (tau < 0) tau = 0;
  if (tau > p.duration) tau = p.duration;
  const j = p.jerk;
  out.s = p.s0 + tau * (p.v0 + tau * (p.a0 / 2 + (tau * j) / 6));
  out.v = p.v0 + tau * (p.a0 + (tau * j) / 2);
  out.a = p.a0 + tau * j;
  return out;
}

export function phasesDuration(phases: readonly Phase[]): number {
  const last = phases[phases.length - 1];
  return last ? last.t0 + last.duration : 0;
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
export function trapezoidPhases(length: number, entry2: number, exit2: number, cruise2: number, accel: number): Phase[] {
  const ve = Math.sqrt(entry2);
  const vx = Math.sqrt(exit2);
  let vp2 = Math.min(cruise2, (2 * accel * length + entry2 + exit2) / 2);
  // Rounding can leave vp² a hair below ve² or vx²; the profile must not dip.
  vp2 = Math.max(vp2, entry2, exit2);
  const vp = Math.sqrt(vp2);
  const dAcc = (vp2 - entry2) / (2 * accel);
  const dDec = (vp2 - exit2) / (2 * accel);
  const dCruise = Math.max(0, length - dAcc - dDec);

  const phases: Phase[] = [];
  let t = 0;
  let s = 0;
  const tAcc = (vp - ve) / accel;
  if (tAcc > 0) {
    phases.push({ t0: t, duration: tAcc, s0: s, v0: ve, a0: accel, jerk: 0 });
    t += tAcc;
    s += dAcc;
  }
  if (dCruise > 0 && vp > 0) {
    const tCruise = dCruise / vp;
    phases.push({ t0: t, duration: tCruise, s0: s, v0: vp, a0: 0, jerk: 0 });
    t += tCruise;
    s += dCruise;
  }
  const tDec = (vp - vx) / accel;
  if (tDec > 0) {
    phases.push({ t0: t, duration: tDec, s0: s, v0: vp, a0: -accel, jerk: 0 });
  }
  if (phases.length === 0) {
    // Only a segment of zero length and zero speed gets here; the queue skips those.
    phases.push({ t0: 0, duration: 0, s0: 0, v0: ve, a0: 0, jerk: 0 });
  }
  return phases;
}
