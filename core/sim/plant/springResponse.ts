/**
 * The belt between a motor and the tool, as a damped spring: the tool (mass on
 * a belt) follows the carriage position u that the motor steps set.
 *
 *   x'' = ω²·(u − x) − 2ζω·x'
 *
 * ω (rad/s) is the natural frequency, ζ the damping ratio. Between two input
 * changes u is constant, so with e = x − u the motion is the free response of
 *
 *   e'' + 2ζω·e' + ω²·e = 0,   e(0) = e₀,  e'(0) = v₀,
 *
 * which has a closed form. We advance the state with it exactly, from input
 * change to input change: no time step, no stability limit, any ω.
 *
 *   underdamped (ζ < 1), ω_d = ω·√(1 − ζ²):
 *     e(t) = e^(−ζωt)·[e₀·cos ω_d t + (v₀ + ζω e₀)/ω_d · sin ω_d t]
 *     e'(t) = e^(−ζωt)·[v₀·cos ω_d t − (ω² e₀ + ζω v₀)/ω_d · sin ω_d t]
 *     (differentiate the first line; the cross terms collect to ω²e₀ since
 *      ζ²ω² + ω_d² = ω²)
 *   critically damped (ζ = 1):
 *     e(t) = [e₀ + (v₀ + ω e₀)·t]·e^(−ωt)
 *     e'(t) = [v₀ − ω(v₀ + ω e₀)·t]·e^(−ωt)
 *   overdamped (ζ > 1), roots r₁,₂ = −ω(ζ ∓ √(ζ² − 1)):
 *     e(t) = A·e^(r₁t) + B·e^(r₂t),  A = (v₀ − r₂e₀)/(r₁ − r₂),  B = e₀ − A
 *     e'(t) = r₁A·e^(r₁t) + r₂B·e^(r₂t)
 *
 * and the acceleration is read off the equation: x'' = −ω²e − 2ζω·x'.
 */
export interface SpringParameters {
  /** Natural frequency, Hz (ω = 2π·f). */
  naturalFrequency_hz: number;
  /** Damping ratio ζ (0.05–0.2 for a belt drive). */
  damping: number;
}

export interface SpringState {
  /** Tool position, mm. */
  x: number;
  /** Tool velocity, mm/s. */
  v: number;
}

const CRITICAL_BAND = 1e-9;

/** The tool's state `dt_s` seconds after `state`, with the carriage held at `u`. */
export function springAfter(state: SpringState, u: number, dt_s: number, p: SpringParameters): SpringState {
  if (dt_s === 0) return { x: state.x, v: state.v };
  const w = 2 * Math.PI * p.naturalFrequency_hz;
  const z = p.damping;
  const e0 = state.x - u;
  const v0 = state.v;
  let e: number;
  let v: number;
  if (z < 1 - CRITICAL_BAND) {
    const wd = w * Math.sqrt(1 - z * z);
    const decay = Math.exp(-z * w * dt_s);
    const c = Math.cos(wd * dt_s);
    const s = Math.sin(wd * dt_s);
    e = decay * (e0 * c + ((v0 + z * w * e0) / wd) * s);
    v = decay * (v0 * c - ((w * w * e0 + z * w * v0) / wd) * s);
  } else if (z <= 1 + CRITICAL_BAND) {
    const decay = Math.exp(-w * dt_s);
    e = (e0 + (v0 + w * e0) * dt_s) * decay;
    v = (v0 - w * (v0 + w * e0) * dt_s) * decay;
  } else {
    const root = Math.sqrt(z * z - 1);
    const r1 = -w * (z - root);
    const r2 = -w * (z + root);
    const a = (v0 - r2 * e0) / (r1 - r2);
    const b = e0 - a;
    const x1 = Math.exp(r1 * dt_s);
    const x2 = Math.exp(r2 * dt_s);
    e = a * x1 + b * x2;
    v = r1 * a * x1 + r2 * b * x2;
  }
  return { x: u + e, v };
}

/** The tool's acceleration, mm/s², in `state` with the carriage at `u`. */
export function springAcceleration(state: SpringState, u: number, p: SpringParameters): number {
  const w = 2 * Math.PI * p.naturalFrequency_hz;
  return -w * w * (state.x - u) - 2 * p.damping * w * state.v;
}
