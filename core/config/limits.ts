/**
 * Kinematic limits, normalised, and their projection onto a direction of travel.
 *
 * Two families of limit may be given together (Klipper uses the first, GRBL the second):
 *  - a scalar bounds the magnitude of the vector: |v| ≤ V, |a| ≤ A;
 *  - a per-axis array bounds each component: |vᵢ| ≤ Vᵢ, |aᵢ| ≤ Aᵢ.
 *
 * Along a straight segment with unit direction u, the velocity vector is v·u and
 * the acceleration vector is a·u (a = s″). So the scalar bounds give |v| ≤ V and
 * the per-axis bounds give |v|·|uᵢ| ≤ Vᵢ, that is |v| ≤ Vᵢ/|uᵢ|. The limit along
 * the path is the smallest of these: see projectLimit().
 */
import { configError } from '../errors.ts';
import type { LimitsConfig, ResolvedLimits } from './types.ts';

export type { ResolvedLimits };

export const DEFAULT_JUNCTION_DEVIATION_MM = 0.05;

function positive(field: string, value: unknown): number {
  if (typeof value !== 'number' || !Number.isFinite(value) || value <= 0) {
    throw configError(field, `must be a positive finite number, got ${String(value)}`);
  }
  return value;
}

/**
 * What the wire and the readers can run, as a [min, max] per kind of limit.
 *  - Speed: below 1 µm/s (moves.ts MIN_SPEED) a speed's square underflows and a
 *    segment's µs outgrow the wire; above 100 m/s a position track's fixed-point
 *    speed (firmware fixed_point.h, ~16 000 units/µs = 250 m/s) has no room left
 *    for a CoreXY actuator's √2.
 *  - Acceleration: the same floor; above 10⁶ mm/s² (100 g) a reader's Q0.32 half
 *    acceleration Δ·α/2 overflows (profile.h FIXED_LIMIT), and TIMING's f32 alpha
 *    = a/L would overflow for the shortest segments long before 4·10³⁸.
 * A limit outside is refused here rather than sent as a TIMING a device refuses.
 */
export const LIMIT_RANGE = { speed: [1e-3, 1e5], accel: [1e-3, 1e6] } as const;

function limit(field: string, value: unknown, kind: keyof typeof LIMIT_RANGE): number {
  const v = positive(field, value);
  const [min, max] = LIMIT_RANGE[kind];
  const unit = kind === 'speed' ? 'mm/s' : 'mm/s²';
  if (v < min || v > max) throw configError(field, `must be between ${min} and ${max} ${unit}, got ${v}`);
  return v;
}

function perAxis(field: string, value: unknown, axes: number, kind: keyof typeof LIMIT_RANGE): number[] {
  if (!Array.isArray(value)) throw configError(field, 'must be an array with one limit per motion axis');
  if (value.length !== axes) {
    throw configError(field, `has ${value.length} entries but there are ${axes} motion axes`);
  }
  return value.map((v, i) => limit(`${field}[${i}]`, v, kind));
}

/** Splits a `number | number[]` limit and its explicit per-axis twin into (scalar, perAxis). */
function resolvePair(
  scalarField: string,
  scalar: unknown,
  axisField: string,
  axis: unknown,
  axes: number,
  kind: keyof typeof LIMIT_RANGE,
): { magnitude: number; perAxis: number[] } {
  let magnitude = Infinity;
  let axisLimits: number[] | undefined;
  if (Array.isArray(scalar)) {
    axisLimits = perAxis(scalarField, scalar, axes, kind);
  } else if (scalar !== undefined) {
    magnitude = limit(scalarField, scalar, kind);
  }
  if (axis !== undefined) {
    if (axisLimits) throw configError(axisField, `per-axis limits are already given as an array in ${scalarField}`);
    axisLimits = perAxis(axisField, axis, axes, kind);
  }
  if (magnitude === Infinity && !axisLimits) {
    throw configError(scalarField, `is required: give a number (bound on the vector magnitude) or an array (one bound per axis)`);
  }
  return { magnitude, perAxis: axisLimits ?? new Array<number>(axes).fill(Infinity) };
}

export function resolveLimits(limits: LimitsConfig | undefined, axes: number, field = 'limits'): ResolvedLimits {
  if (limits === null || typeof limits !== 'object') throw configError(field, 'must be an object');
  const known = new Set(['maxVelocity', 'maxAcceleration', 'axisMaxVelocity', 'axisMaxAcceleration', 'junctionDeviation']);
  for (const key of Object.keys(limits)) {
    if (!known.has(key)) throw configError(`${field}.${key}`, `is not a known limit (known: ${[...known].join(', ')})`);
  }
  const v = resolvePair(`${field}.maxVelocity`, limits.maxVelocity, `${field}.axisMaxVelocity`, limits.axisMaxVelocity, axes, 'speed');
  const a = resolvePair(
    `${field}.maxAcceleration`,
    limits.maxAcceleration,
    `${field}.axisMaxAcceleration`,
    limits.axisMaxAcceleration,
    axes,
    'accel',
  );
  const junctionDeviation =
    limits.junctionDeviation === undefined
      ? DEFAULT_JUNCTION_DEVIATION_MM
      : positive(`${field}.junctionDeviation`, limits.junctionDeviation);
  return {
    maxSpeed: v.magnitude,
    maxAccel: a.magnitude,
    axisMaxSpeed: v.perAxis,
    axisMaxAccel: a.perAxis,
    junctionDeviation,
  };
}

/**
 * The largest scalar L such that a vector L·u respects both the magnitude bound and
 * every per-axis bound: min(magnitude, minᵢ perAxisᵢ/|uᵢ|). `u` is a unit vector.
 */
export function projectLimit(magnitude: number, perAxisLimits: readonly number[], u: readonly number[]): number {
  let limit = magnitude;
  for (let i = 0; i < u.length; i++) {
    const axisLimit = perAxisLimits[i];
    if (axisLimit === Infinity) continue; // unbounded axis: ∞/|uᵢ| never lowers the limit (and a division is slow)
    const c = Math.abs(u[i]);
    if (c > 0) {
      const projected = axisLimit / c;
      if (projected < limit) limit = projected;
    }
  }
  return limit;
}

/** Whether any axis has a finite limit, so that projectLimit() depends on the direction. */
export function boundsAnAxis(perAxisLimits: readonly number[]): boolean {
  for (let i = 0; i < perAxisLimits.length; i++) if (perAxisLimits[i] !== Infinity) return true;
  return false;
}
