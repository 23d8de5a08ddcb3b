/**
 * Transforms map motion axes (cartesian, say x and y) to actuator axes (the
 * motors, say a and b). Both kinds of track are available to readers.
 *
 *  - CoreXY and H-bot: a = x + y, b = x − y. The two share kinematics; they differ
 *    mechanically (an H-bot's belt racks the gantry).
 *  - linear: any matrix, to = M·from.
 *  - function: any function. Treated as nonlinear unless declared linear.
 *
 * A linear map sends a line to a line, so an actuator track over a segment is
 * exactly T(start) + (M·u)·s. A nonlinear map bends lines into curves, so the
 * segment is subdivided until the straight chords in actuator space stay within
 * the transform's tolerance of the true curve, at every path position s (the
 * error that matters is where the motor is at a given moment, not the chord's
 * distance to the curve).
 */
import { MaxlError, configError } from '../errors.ts';
import type { ResolvedTransform, TransformConfig } from './types.ts';

export const DEFAULT_TRANSFORM_TOLERANCE_MM = 0.01;
/**
 * The finest tolerance a function transform may ask for (output units, mm): 0.1 µm,
 * far below a step. A finer one (5e-324) would subdivide every move into the most
 * pieces allowed.
 */
export const MIN_TRANSFORM_TOLERANCE_MM = 1e-4;
/** Subdivision never goes deeper than 2^MAX_DEPTH pieces per segment, even near a singularity. */
const MAX_DEPTH = 24;
/**
 * A move that needs more pieces than this to stay within the tolerance is refused
 * (MOVE_INVALID), not queued as millions of segments: deep refinement at one
 * singular point takes a few dozen, a whole move that fine is a mistake.
 */
export const MAX_PIECES_PER_MOVE = 10_000;

export type { ResolvedTransform };

function matrixTransform(matrix: number[][]): (input: readonly number[]) => number[] {
  return (input) => matrix.map((row) => row.reduce((acc, m, i) => acc + m * input[i], 0));
}

const COREXY = [
  [1, 1],
  [1, -1],
];

export function resolveTransforms(configs: TransformConfig[] | undefined, motionAxes: string[]): ResolvedTransform[] {
  if (configs === undefined) return [];
  if (!Array.isArray(configs)) throw configError('transforms', 'must be an array');
  return configs.map((t, n) => {
    const field = `transforms[${n}]`;
    if (t === null || typeof t !== 'object') throw configError(field, 'must be an object');
    if (!Array.isArray(t.from) || t.from.length === 0) throw configError(`${field}.from`, 'must be a non-empty array of motion axis names');
    if (!Array.isArray(t.to) || t.to.length === 0) throw configError(`${field}.to`, 'must be a non-empty array of actuator axis names');
    const inputs = t.from.map((name, i) => {
      const index = motionAxes.indexOf(name);
      if (index < 0) throw configError(`${field}.from[${i}]`, `"${String(name)}" is not a motion axis (motion axes: ${motionAxes.join(', ')})`);
      return index;
    });
    const tolerance = t.type === 'function' && t.tolerance !== undefined ? t.tolerance : DEFAULT_TRANSFORM_TOLERANCE_MM;
    if (!(typeof tolerance === 'number' && tolerance >= MIN_TRANSFORM_TOLERANCE_MM && Number.isFinite(tolerance))) {
      throw configError(`${field}.tolerance`, `must be a finite number ≥ ${MIN_TRANSFORM_TOLERANCE_MM} (output units, mm by default), got ${String(tolerance)}`);
    }
    switch (t.type) {
      case 'corexy':
      case 'hbot':
        if (t.from.length !== 2) throw configError(`${field}.from`, `${t.type} takes 2 inputs, got ${t.from.length}`);
        if (t.to.length !== 2) throw configError(`${field}.to`, `${t.type} gives 2 outputs, got ${t.to.length}`);
        return { type: t.type, inputs, outputs: [...t.to], linear: true, tolerance, evaluate: matrixTransform(COREXY) };
      case 'linear': {
        const m = t.matrix;
        if (!Array.isArray(m) || m.length !== t.to.length) {
          throw configError(`${field}.matrix`, `must have one row per output (${t.to.length})`);
        }
        m.forEach((row, r) => {
          if (!Array.isArray(row) || row.length !== t.from.length) {
            throw configError(`${field}.matrix[${r}]`, `must have one column per input (${t.from.length})`);
          }
          row.forEach((v, c) => {
            if (typeof v !== 'number' || !Number.isFinite(v)) throw configError(`${field}.matrix[${r}][${c}]`, 'must be a finite number');
          });
        });
        return { type: 'linear', inputs, outputs: [...t.to], linear: true, tolerance, evaluate: matrixTransform(m) };
      }
      case 'function': {
        if (typeof t.fn !== 'function') throw configError(`${field}.fn`, 'must be a function from inputs to outputs');
        const fn = t.fn;
        const outputs = t.to.length;
        const names = [...t.to];
        // A user's function may throw or return anything: every failure becomes a
        // MaxlError naming the point, before any segment is made from it.
        const evaluate = (input: readonly number[]): number[] => {
          let out: unknown;
          try {
            out = fn(input);
          } catch (err) {
            throw new MaxlError('MOVE_INVALID', `the transform threw at (${input.join(', ')}): ${err instanceof Error ? err.message : String(err)}`, `${field}.fn`);
          }
          if (!Array.isArray(out) || out.length !== outputs) {
            throw configError(`${field}.fn`, `must return ${outputs} numbers, returned ${Array.isArray(out) ? out.length : typeof out}`);
          }
          for (let o = 0; o < outputs; o++) {
            const v: unknown = out[o];
            if (typeof v !== 'number' || !Number.isFinite(v)) {
              throw new MaxlError('MOVE_INVALID', `gave ${String(v)} for ${names[o]} at (${input.join(', ')}): a transform must give finite numbers`, `${field}.fn`);
            }
          }
          return out as number[];
        };
        return { type: 'function', inputs, outputs: [...t.to], linear: t.linear === true, tolerance, evaluate };
      }
      default:
        throw configError(`${field}.type`, `"${String((t as { type: unknown }).type)}" is not a transform type (corexy, hbot, linear, function)`);
    }
  });
}

/** What actuatorPosition gives on a machine without transforms: one shared empty array. */
export const NO_ACTUATORS: number[] = [];
const NONE = NO_ACTUATORS;

/** Every actuator axis's position at the motion-space point p, in config order. */
export function actuatorPosition(transforms: readonly ResolvedTransform[], p: readonly number[]): number[] {
  if (transforms.length === 0) return NONE;
  const out: number[] = [];
  for (const t of transforms) {
    const input = t.inputs.map((i) => p[i]);
    for (const v of t.evaluate(input)) out.push(v);
  }
  return out;
}

function lerp(a: readonly number[], b: readonly number[], f: number): number[] {
  return a.map((v, i) => v + (b[i] - v) * f);
}

/**
 * Fractions 0 = f₀ < f₁ < … < fₙ = 1 along the line p0→p1 such that, for every
 * nonlinear transform T and every piece [fₖ, fₖ₊₁], the chord from T(p(fₖ)) to
 * T(p(fₖ₊₁)) stays within T's tolerance of T(p(f)) at the same f, on every output.
 *
 * Each piece is tested at ¼, ½ and ¾ of its span and halved while any error
 * exceeds the tolerance, judged by the peak between the samples (peakOfSamples),
 * not by the samples alone. Tests check the result by dense sampling.
 */
/** Where a piece is tested, as fractions of its span. */
const QUARTERS = [0.25, 0.5, 0.75];

/** Steps of the grid on which peakOfSamples reads the quartic through the samples. */
const PEAK_GRID = 64;

/**
 * The Lagrange basis of the five points 0, ¼, ½, ¾, 1 at x: only the three inner ones,
 * as the error is 0 at both ends. L_i(x) = Π_{j≠i} (x − x_j)/(x_i − x_j).
 */
function innerBasis(x: number): number[] {
  const xs = [0, ...QUARTERS, 1];
  return QUARTERS.map((_, n) => {
    const i = n + 1;
    let l = 1;
    for (let j = 0; j < xs.length; j++) if (j !== i) l *= (x - xs[j]) / (xs[i] - xs[j]);
    return l;
  });
}

/** innerBasis at each point of the grid, k/PEAK_GRID for k = 0 … PEAK_GRID. */
const GRID_BASIS = Array.from({ length: PEAK_GRID + 1 }, (_, k) => innerBasis(k / PEAK_GRID));

/**
 * The peak |e| over a piece of an error sampled at ¼, ½ and ¾ (and 0 at both ends):
 * the peak of the quartic through those five points. Three samples alone miss it:
 * a flat-topped error (a polar θ across a wide arc) peaks beside the middle sample,
 * and one bent hard at one end (θ near the pole) peaks between two samples; either
 * let a piece through whose error passed the tolerance (by 1.3e-4 and 1.3e-6 of it:
 * a dense check found both). The quartic follows both shapes (to 1e-5 of the
 * tolerance on those pieces, or above them). Its peak is read on a grid of
 * PEAK_GRID steps and refined by parabolaPeak at the grid's largest value.
 */
export function peakOfSamples(e1: number, e2: number, e3: number): number {
  const values = GRID_BASIS.map(([l1, l2, l3]) => e1 * l1 + e2 * l2 + e3 * l3);
  return parabolaPeak(values);
}

/**
 * The peak |v| of values sampled at evenly spaced points, estimated by the parabola
 * through the largest |v| (not an end) and its two neighbours.
 *
 * With z = v·sign(v_i) at the largest sample i and its neighbours z₋, z₀, z₊ at
 * x = −1, 0, 1 (in sample steps), the parabola is z(x) = z₀ + b·x + c·x² with
 * b = (z₊ − z₋)/2 and c = (z₊ − 2·z₀ + z₋)/2. As z₀ ≥ |v₋|, |v₊| ≥ z₋, z₊: c ≤ 0, and
 * |z₊ − z₋| ≤ (z₀ − z₊) + (z₀ − z₋) = −2c gives |b| ≤ −c, so its vertex x* = −b/2c lies
 * within half a step of sample i, and its top is z(x*) = z₀ − b²/4c ≥ z₀ (= z₀ when
 * c = 0, a flat run).
 */
function parabolaPeak(values: readonly number[]): number {
  let i = 1;
  for (let j = 2; j + 1 < values.length; j++) if (Math.abs(values[j]) > Math.abs(values[i])) i = j;
  const sign = values[i] < 0 ? -1 : 1;
  const z0 = sign * values[i];
  const zMinus = sign * values[i - 1];
  const zPlus = sign * values[i + 1];
  const b = (zPlus - zMinus) / 2;
  const c = (zPlus - 2 * z0 + zMinus) / 2;
  return c < 0 ? z0 - (b * b) / (4 * c) : z0;
}

export function subdivisionFractions(
  transforms: readonly ResolvedTransform[],
  p0: readonly number[],
  p1: readonly number[],
): number[] {
  const nonlinear = transforms.filter((t) => !t.linear);
  if (nonlinear.length === 0) return [0, 1];
  const at = (f: number) => {
    const p = lerp(p0, p1, f);
    return nonlinear.map((t) => t.evaluate(t.inputs.map((i) => p[i])));
  };
  const fractions = [0];
  const split = (f0: number, y0: number[][], f1: number, y1: number[][], depth: number): void => {
    const ys = QUARTERS.map((q) => at(f0 + (f1 - f0) * q));
    let worst = 0;
    nonlinear.forEach((t, k) => {
      for (let o = 0; o < y0[k].length; o++) {
        // The chord error at ¼, ½ and ¾ of the piece (0 at both ends).
        const [e1, e2, e3] = QUARTERS.map((q, i) => ys[i][k][o] - (y0[k][o] + (y1[k][o] - y0[k][o]) * q));
        worst = Math.max(worst, peakOfSamples(e1, e2, e3) / t.tolerance);
      }
    });
    if (worst <= 1 || depth >= MAX_DEPTH) {
      fractions.push(f1);
      if (fractions.length > MAX_PIECES_PER_MOVE + 1) {
        throw new MaxlError(
          'MOVE_INVALID',
          `a nonlinear transform needs more than ${MAX_PIECES_PER_MOVE} pieces to follow this move within its tolerance: raise the tolerance or split the move`,
          'endPosition',
        );
      }
      return;
    }
    const fm = (f0 + f1) / 2;
    const ym = at(fm);
    split(f0, y0, fm, ym, depth + 1);
    split(fm, ym, f1, y1, depth + 1);
  };
  split(0, at(0), 1, at(1), 0);
  return fractions;
}
