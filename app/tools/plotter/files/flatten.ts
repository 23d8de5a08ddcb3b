/**
 * Curves to polylines within a chord tolerance: the greatest distance between a
 * curve and the chords that replace it.
 *
 * The bound every function here uses. Let C(t) be a C² curve on [t0, t0 + h] and
 * L(t) the linear interpolation between C(t0) and C(t0 + h). The error of linear
 * interpolation is
 *
 *   |C(t) − L(t)| ≤ h²/8 · max |C''|
 *
 * (per coordinate, by the remainder of Lagrange interpolation; for the vector, apply
 * it to the component of C − L along any unit vector, which has the same form).
 * L(t) lies on the chord, so every curve point is within that of the chord, and
 * every chord point L(t) is within it of the curve point C(t): the Hausdorff
 * distance between the curve and its chords is at most h²/8 · max |C''|.
 *
 * Split the parameter range H into n equal steps h = H/n; the error is ≤ tol when
 *
 *   n ≥ H · sqrt(max |C''| / (8 · tol)).
 *
 * - Cubic Bézier on t ∈ [0, 1]: C'' = 6[(1−t)(P0 − 2P1 + P2) + t(P1 − 2P2 + P3)], a
 *   convex combination, so max |C''| ≤ 6 · max(|P0 − 2P1 + P2|, |P1 − 2P2 + P3|).
 * - Quadratic: C'' = 2(P0 − 2P1 + P2), constant.
 * - Elliptical arc with radii rx, ry over the parameter sweep Δθ:
 *   C(θ) = c + R(φ)(rx cos θ, ry sin θ), C'' = −R(φ)(rx cos θ, ry sin θ), so
 *   |C''| ≤ max(rx, ry) and n ≥ |Δθ| · sqrt(max(rx, ry) / (8 · tol)). (For a
 *   circle this is the sagitta r(1 − cos(h/2)) ≤ r h²/8.)
 *
 * All coordinates here are already in the units the tolerance is in (mm).
 */

/** mm: the default chord tolerance of every importer. */
export const DEFAULT_CHORD_TOLERANCE_MM = 0.02;

/** At most this many chords per curve, so that a degenerate input cannot exhaust memory. */
const MAX_STEPS = 100_000;

export function stepsFor(range: number, maxSecondDerivative: number, tol: number): number {
  if (!(maxSecondDerivative > 0) || !(range > 0)) return 1;
  const n = Math.ceil(range * Math.sqrt(maxSecondDerivative / (8 * tol)));
  return Math.min(MAX_STEPS, Math.max(1, n));
}

/** Appends the cubic from (x0, y0) through controls (x1, y1), (x2, y2) to (x3, y3), without its first point. */
export function flattenCubic(out: number[], x0: number, y0: number, x1: number, y1: number, x2: number, y2: number, x3: number, y3: number, tol: number): void {
  const ax = x0 - 2 * x1 + x2, ay = y0 - 2 * y1 + y2;
  const bx = x1 - 2 * x2 + x3, by = y1 - 2 * y2 + y3;
  const n = stepsFor(1, 6 * Math.max(Math.hypot(ax, ay), Math.hypot(bx, by)), tol);
  for (let i = 1; i <= n; i++) {
    const t = i / n, u = 1 - t;
    const b0 = u * u * u, b1 = 3 * u * u * t, b2 = 3 * u * t * t, b3 = t * t * t;
    out.push(b0 * x0 + b1 * x1 + b2 * x2 + b3 * x3, b0 * y0 + b1 * y1 + b2 * y2 + b3 * y3);
  }
}

/** Appends the quadratic from (x0, y0) through (x1, y1) to (x2, y2), without its first point. */
export function flattenQuadratic(out: number[], x0: number, y0: number, x1: number, y1: number, x2: number, y2: number, tol: number): void {
  const n = stepsFor(1, 2 * Math.hypot(x0 - 2 * x1 + x2, y0 - 2 * y1 + y2), tol);
  for (let i = 1; i <= n; i++) {
    const t = i / n, u = 1 - t;
    out.push(u * u * x0 + 2 * u * t * x1 + t * t * x2, u * u * y0 + 2 * u * t * y1 + t * t * y2);
  }
}

/** An ellipse arc by its centre: c + R(phi)(rx cos θ, ry sin θ) for θ from theta0 over dtheta. */
export interface CenterArc {
  cx: number;
  cy: number;
  rx: number;
  ry: number;
  /** rad, the x axis's rotation */
  phi: number;
  theta0: number;
  dtheta: number;
}

/** Appends the arc's points after its first, the last one exactly `end` when given. */
export function flattenCenterArc(out: number[], a: CenterArc, tol: number, end?: readonly [number, number]): void {
  const n = stepsFor(Math.abs(a.dtheta), Math.max(a.rx, a.ry), tol);
  const cos = Math.cos(a.phi), sin = Math.sin(a.phi);
  for (let i = 1; i <= n; i++) {
    if (i === n && end) {
      out.push(end[0], end[1]);
      break;
    }
    const th = a.theta0 + (a.dtheta * i) / n;
    const ex = a.rx * Math.cos(th), ey = a.ry * Math.sin(th);
    out.push(a.cx + cos * ex - sin * ey, a.cy + sin * ex + cos * ey);
  }
}

/**
 * SVG's endpoint arc (the `A` command) to its centre form, as in SVG 1.1 §F.6.5,
 * with the radii scaled up when they are too small to reach the end (F.6.6).
 * Null when the arc is a straight line (a zero radius) or empty (start = end).
 */
export function svgArcToCenter(
  x1: number,
  y1: number,
  rxIn: number,
  ryIn: number,
  xAxisRotationDeg: number,
  largeArc: boolean,
  sweep: boolean,
  x2: number,
  y2: number,
): CenterArc | null {
  if (x1 === x2 && y1 === y2) return null;
  let rx = Math.abs(rxIn), ry = Math.abs(ryIn);
  if (rx === 0 || ry === 0) return null;
  const phi = (xAxisRotationDeg * Math.PI) / 180;
  const cos = Math.cos(phi), sin = Math.sin(phi);
  // Step 1: the midpoint in the ellipse's frame.
  const dx = (x1 - x2) / 2, dy = (y1 - y2) / 2;
  const x1p = cos * dx + sin * dy;
  const y1p = -sin * dx + cos * dy;
  // F.6.6: scale the radii up if no ellipse of these radii reaches both ends.
  const lambda = (x1p * x1p) / (rx * rx) + (y1p * y1p) / (ry * ry);
  if (lambda > 1) {
    const s = Math.sqrt(lambda);
    rx *= s;
    ry *= s;
  }
  // Step 2: the centre in the ellipse's frame.
  const rx2 = rx * rx, ry2 = ry * ry;
  const num = rx2 * ry2 - rx2 * y1p * y1p - ry2 * x1p * x1p;
  const den = rx2 * y1p * y1p + ry2 * x1p * x1p;
  let k = Math.sqrt(Math.max(0, num / den));
  if (largeArc === sweep) k = -k;
  const cxp = (k * rx * y1p) / ry;
  const cyp = (-k * ry * x1p) / rx;
  // Step 3: the centre in user space.
  const cx = cos * cxp - sin * cyp + (x1 + x2) / 2;
  const cy = sin * cxp + cos * cyp + (y1 + y2) / 2;
  // Step 4: the angles.
  const ux = (x1p - cxp) / rx, uy = (y1p - cyp) / ry;
  const vx = (-x1p - cxp) / rx, vy = (-y1p - cyp) / ry;
  const theta0 = Math.atan2(uy, ux);
  let dtheta = Math.atan2(ux * vy - uy * vx, ux * vx + uy * vy);
  if (!sweep && dtheta > 0) dtheta -= 2 * Math.PI;
  else if (sweep && dtheta < 0) dtheta += 2 * Math.PI;
  return { cx, cy, rx, ry, phi, theta0, dtheta };
}
