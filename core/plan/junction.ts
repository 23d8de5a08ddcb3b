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
 * The half-angle comes from the vectors without trigonometry, and without the
 * cancellation of √((1 − cos θ)/2) near a reversal: −u_in and u_out are unit
 * vectors θ apart, so |u_out − (−u_in)| = 2·sin(θ/2) and |u_out + (−u_in)| =
 * 2·cos(θ/2). Writing 1 − sin(θ/2) = cos²(θ/2)/(1 + sin(θ/2)) keeps the straight-on
 * case exact too:
 *   v² = a·δ·sin(θ/2)·(1 + sin(θ/2)) / cos²(θ/2),
 * infinite (no limit) for a straight line and 0 for a full reversal.
 *
 * At the corner the velocity vector turns from v·u_in to v·u_out, a change along
 * u_out − u_in, so the acceleration limit used is the one projected on that
 * direction (per-axis limits make it direction dependent).
 */
import { boundsAnAxis, projectLimit, type ResolvedLimits } from '../config/limits.ts';

/** Max junction speed² (mm²/s²) between unit directions uIn and uOut. Infinity for a straight line. */
export function junctionSpeed2(uIn: readonly number[], uOut: readonly number[], limits: ResolvedLimits): number {
  return cornerSpeed2(uIn, uOut, limits, boundsAnAxis(limits.axisMaxAccel));
}

/** junctionSpeed2 given whether any axis has an acceleration limit of its own (boundsAnAxis(limits.axisMaxAccel)), for callers that know it once. */
export function cornerSpeed2(uIn: readonly number[], uOut: readonly number[], limits: ResolvedLimits, accelPerAxis: boolean): number {
  let sum2 = 0;
  let diff2 = 0;
  for (let i = 0; i < uIn.length; i++) {
    const s = uOut[i] + uIn[i];
    const d = uOut[i] - uIn[i];
    sum2 += s * s;
    diff2 += d * d;
  }
  const sinHalf = Math.sqrt(sum2) / 2;
  const cosHalf = Math.sqrt(diff2) / 2;
  if (cosHalf === 0) return Infinity; // straight on
  if (sinHalf === 0) return 0; // full reversal
  const accel = accelPerAxis
    ? projectLimit(limits.maxAccel, limits.axisMaxAccel, changeDirection(uIn, uOut, cosHalf))
    : limits.maxAccel; // a bound on |a| alone is the same in every direction
  return (accel * limits.junctionDeviation * sinHalf * (1 + sinHalf)) / (cosHalf * cosHalf);
}

/** Reused by changeDirection(): a corner is planned a million times a second, and nothing keeps its direction. */
let changeBuffer: number[] = [];

/** Direction of the velocity change at the corner, (u_out − u_in) / |u_out − u_in|, where |u_out − u_in| = 2·cos(θ/2). */
function changeDirection(uIn: readonly number[], uOut: readonly number[], cosHalf: number): number[] {
  if (changeBuffer.length !== uIn.length) changeBuffer = new Array<number>(uIn.length).fill(0);
  for (let i = 0; i < uIn.length; i++) changeBuffer[i] = (uOut[i] - uIn[i]) / (2 * cosHalf);
  return changeBuffer;
}
