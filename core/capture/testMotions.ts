/**
 * The capture tool's test motions, as plain MAXL moves along one axis.
 *
 * Resonance sweep (after Klipper's TEST_RESONANCES, its vibration test generator): short
 * back-and-forth moves whose frequency rises steadily. One cycle at frequency f goes out
 * by d and back:
 *
 *   out:  accelerate at a for T/4, decelerate at a for T/4        T = 1/f
 *   back: the same, the other way
 *
 * so the acceleration is a square wave +a, −a, −a, +a of period T (fundamental f), the
 * peak speed a·T/4 and the stroke d = a·(T/4)² = a / (16 f²). Each move is a triangle
 * profile: a rest-to-rest move of length d capped at acceleration a (the move's
 * maxAcceleration) peaks at √(a·d) = a·T/4, and it ends at rest because the next move
 * reverses (the junction speed of a reversal is 0). As in Klipper the amplitude grows with
 * frequency, a = accelPerHz·f (capped at the machine's limit; Klipper's default is 60),
 * which keeps the stroke from vanishing at high f (d = accelPerHz / (16 f)), and the
 * frequency rises by hzPerSecond·T per cycle (Klipper: by hz_per_sec per second, a half
 * cycle at a time), so the sweep spends equal time at every frequency. (Recent Klipper also
 * lays a slow back-and-forth "sweeping" motion over the vibrations; not done here.)
 *
 * Growing moves: strokes of a fixed length out and back along the axis, their speed (or
 * acceleration) stepping from `from` to `to` over `steps` strokes, the other limit left at
 * the machine's.
 */
import type { ResolvedConfig } from '../config/types.ts';
import type { LinearMove } from '../trajectory/moves.ts';

export type TestMotion =
  | { kind: 'sweep'; axis: string; fromHz: number; toHz: number; hzPerSecond: number; accelPerHz: number }
  | { kind: 'growing'; axis: string; grow: 'speed' | 'acceleration'; stroke_mm: number; from: number; to: number; steps: number };

export interface MachineLimits {
  motionAxes: readonly string[];
  /** mm/s and mm/s² along the axis */
  maxVelocity: number;
  maxAcceleration: number;
  /** soft limits of the axis, mm */
  min: number;
  max: number;
}

export interface PlannedMotion {
  moves: LinearMove[];
  /** the time the motion takes by its own arithmetic, s (the planner's real profile is the same for a sweep) */
  duration_s: number;
  /** where its excitation is, for the spectrum's peak search */
  band_hz: [number, number];
  description: string;
}

/** The limits along one motion axis of a resolved config (the scalar and the axis's own, whichever is lower). */
export function limitsAlong(config: ResolvedConfig, axis: string): MachineLimits {
  const i = config.motionAxes.indexOf(axis);
  if (i < 0) throw new TestMotionError('axis', `"${axis}" is not a motion axis (${config.motionAxes.join(', ')})`);
  const l = config.limits;
  return {
    motionAxes: config.motionAxes,
    maxVelocity: Math.min(l.maxSpeed, l.axisMaxSpeed[i]),
    maxAcceleration: Math.min(l.maxAccel, l.axisMaxAccel[i]),
    min: config.softMin[i],
    max: config.softMax[i],
  };
}

/** Thrown with a field name and a sentence, before any move is made. */
export class TestMotionError extends Error {
  constructor(
    readonly field: string,
    message: string,
  ) {
    super(`${field}: ${message}`);
  }
}

function positive(field: string, v: number): number {
  if (!Number.isFinite(v) || v <= 0) throw new TestMotionError(field, `must be a positive number, got ${v}`);
  return v;
}

/** The moves of a test motion starting at `start` (one position per motion axis). */
export function planTestMotion(motion: TestMotion, limits: MachineLimits, start: readonly number[]): PlannedMotion {
  const axis = limits.motionAxes.indexOf(motion.axis);
  if (axis < 0) throw new TestMotionError('axis', `"${motion.axis}" is not a motion axis (${limits.motionAxes.join(', ')})`);
  return motion.kind === 'sweep' ? sweep(motion, limits, start, axis) : growing(motion, limits, start, axis);
}

function sweep(m: Extract<TestMotion, { kind: 'sweep' }>, limits: MachineLimits, start: readonly number[], axis: number): PlannedMotion {
  const from = positive('fromHz', m.fromHz);
  const to = positive('toHz', m.toHz);
  const rate = positive('hzPerSecond', m.hzPerSecond);
  const perHz = positive('accelPerHz', m.accelPerHz);
  if (to <= from) throw new TestMotionError('toHz', `must be above fromHz (${from} Hz), got ${to} Hz`);
  if ((to - from) / rate > 600) throw new TestMotionError('hzPerSecond', `the sweep would take ${Math.round((to - from) / rate)} s; keep it under 10 minutes`);
  const widest = Math.min(perHz * from, limits.maxAcceleration) / (16 * from * from);
  const c = start[axis];
  if (c < limits.min || c + widest > limits.max) {
    throw new TestMotionError('axis', `the sweep strokes ${widest.toFixed(2)} mm from ${c} mm, outside ${motionRange(limits)}: move the tool away from the end first`);
  }
  const moves: LinearMove[] = [];
  let f = from;
  let t = 0;
  while (f <= to + 1e-9) {
    const T = 1 / f;
    const a = Math.min(perHz * f, limits.maxAcceleration);
    const d = a / (16 * f * f);
    const v = (a * T) / 4;
    const out = [...start];
    out[axis] = c + d;
    if (v > limits.maxVelocity) throw new TestMotionError('accelPerHz', `at ${f.toFixed(1)} Hz the stroke would need ${v.toFixed(1)} mm/s, above the machine's ${limits.maxVelocity} mm/s: lower accelPerHz or raise fromHz`);
    moves.push({ endPosition: out, maxAcceleration: a }, { endPosition: [...start], maxAcceleration: a });
    t += T;
    f += rate * T;
  }
  return { moves, duration_s: t, band_hz: [from, to], description: `resonance sweep ${motionAxisName(limits, axis)} ${from}–${to} Hz at ${rate} Hz/s` };
}

function growing(m: Extract<TestMotion, { kind: 'growing' }>, limits: MachineLimits, start: readonly number[], axis: number): PlannedMotion {
  const stroke = positive('stroke_mm', m.stroke_mm);
  const from = positive('from', m.from);
  const to = positive('to', m.to);
  const steps = Math.round(m.steps);
  if (!(steps >= 1 && steps <= 200)) throw new TestMotionError('steps', `must be 1 … 200, got ${m.steps}`);
  const cap = m.grow === 'speed' ? limits.maxVelocity : limits.maxAcceleration;
  if (to > cap) throw new TestMotionError('to', `${to} is above the machine's ${m.grow === 'speed' ? 'maximum speed' : 'maximum acceleration'} ${cap}`);
  const c = start[axis];
  const dir = c + stroke <= limits.max ? 1 : c - stroke >= limits.min ? -1 : 0;
  if (dir === 0) throw new TestMotionError('stroke_mm', `a ${stroke} mm stroke from ${c} mm does not fit in ${motionRange(limits)}`);
  const moves: LinearMove[] = [];
  let duration = 0;
  for (let k = 0; k < steps; k++) {
    const value = steps === 1 ? to : from + ((to - from) * k) / (steps - 1);
    const v = m.grow === 'speed' ? value : limits.maxVelocity;
    const a = m.grow === 'speed' ? limits.maxAcceleration : value;
    const out = [...start];
    out[axis] = c + dir * stroke;
    const limitsOfMove = m.grow === 'speed' ? { maxVelocity: v } : { maxAcceleration: a };
    moves.push({ endPosition: out, ...limitsOfMove }, { endPosition: [...start], ...limitsOfMove });
    duration += 2 * strokeTime(stroke, v, a);
  }
  const unit = m.grow === 'speed' ? 'mm/s' : 'mm/s²';
  return { moves, duration_s: duration, band_hz: [1, Infinity], description: `${steps} strokes of ${stroke} mm on ${motionAxisName(limits, axis)}, ${m.grow} ${from}–${to} ${unit}` };
}

/** Time of a rest-to-rest stroke of length L at speed cap v and acceleration a (trapezoid or triangle). */
export function strokeTime(L: number, v: number, a: number): number {
  const ramp = (v * v) / a;
  return L >= ramp ? L / v + v / a : 2 * Math.sqrt(L / a);
}

function motionRange(limits: MachineLimits): string {
  return `the soft limits [${limits.min}, ${limits.max}] mm`;
}

function motionAxisName(limits: MachineLimits, axis: number): string {
  return limits.motionAxes[axis];
}
