/**
 * The junction-deviation speed limit at a corner (GRBL's formula).
 *
 * Let θ be the angle between the reversed incoming direction −u_in and the
 * outgoing direction u_out, so θ = π for a straight continuation and θ = 0 for a
 * full reversal: cos θ = −u_in·u_out.
 *
 * Replace the sharp corner by a circular arc of radius R tangent to both lines.
 * The arc's centre lies on the bisector of the corner at distance R/sin(θ/2) from
 * the vertex, so the arc passes the vertex at distance
 *   δ = R/sin(θ/2) − R.
 * Solving for R with δ the junction deviation:
 *   R = δ·sin(θ/2) / (1 − sin(θ/2)).
 * Going round that arc at speed v needs a centripetal acceleration v²/R, and
 * bounding it by the acceleration limit a gives
 *   v² ≤ a·R = a·δ·sin(θ/2) / (1 − sin(θ/2)).
 * The half-angle comes from cos θ without trigonometry: sin(θ/2) = √((1 − cos θ)/2).
 *
 * At the corner the velocity vector turns from v·u_in to v·u_out, a change along
 * u_out − u_in, so the acceleration limit used is the one projected on that
 * direction (per-axis limits make it direction dependent).
 */
import { projectLimit, type ResolvedLimits } from '../config/limits.ts';

/** Below this, cos θ is treated as a straight line (no limit) or a reversal (stop). */
const STRAIGHT_EPS = 1e-12;

/** Max junction speed² (mm²/s²) between unit directions uIn and uOut. Infinity for a straight line. */
export function junctionSpeed2(uIn: readonly number[], uOut: readonly number[], limits: ResolvedLimits): number {
  let dot = 0;
  for (let i = 0; i < uIn.length; i++) dot += uIn[i] * uOut[i];
  const cosTheta = -dot;
  if (cosTheta <= -1 + STRAIGHT_EPS) return Infinity; // straight on
  if (cosTheta >= 1 - STRAIGHT_EPS) return 0; // full reversal

  // Direction of the velocity change at the corner.
  const change = new Array<number>(uIn.length);
  let norm2 = 0;
  for (let i = 0; i < uIn.length; i++) {
    const d = uOut[i] - uIn[i];
    change[i] = d;
    norm2 += d * d;
  }
  const norm = Math.sqrt(norm2);
  for (let i = 0; i < change.length; i++) change[i] /= norm;
  const accel = projectLimit(limits.maxAccel, limits.axisMaxAccel, change);

  const sinHalf = Math.sqrt((1 - cosTheta) / 2);
  return (accel * limits.junctionDeviation * sinHalf) / (1 - sinHalf);
}
