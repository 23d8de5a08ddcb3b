/**
 * From a move request (an end position, a speed cap, event values) to segments:
 * validation, soft limits, zero-length skipping, subdivision for nonlinear
 * transforms, and each segment's planner inputs (limits projected on its direction,
 * the junction cap with the segment before).
 */
import { MaxlError } from '../errors.ts';
import { projectLimit } from '../config/limits.ts';
import type { ResolvedConfig } from '../config/types.ts';
import { junctionSpeed2 } from '../plan/junction.ts';
import { resolveMoveEvents, type MoveEvents, type ResolvedEventSpec } from './events.ts';
import { Segment } from './segment.ts';
import { actuatorPosition, subdivisionFractions } from './transforms.ts';

export interface LinearMove {
  /** mm: one value per motion axis, or an object naming only the axes that move. */
  endPosition: number[] | Record<string, number>;
  /** mm/s cap on the speed along this move. Defaults to the machine limits. */
  maxVelocity?: number;
  /** mm/s² cap on the acceleration along this move (below the machine limits, as Klipper's M204). */
  maxAcceleration?: number;
  eventChannels?: MoveEvents;
}

/**
 * A dwell: the machine holds its position at rest for `dwell_s` seconds, and its
 * events are set at the dwell's start. A dwell of 0 s is an event-only move.
 */
export interface DwellMove {
  dwell_s: number;
  eventChannels?: MoveEvents;
}

export type Move = LinearMove | DwellMove;

export function isDwell(move: Move): move is DwellMove {
  return move !== null && typeof move === 'object' && 'dwell_s' in move;
}

/**
 * A move that passed validation, not yet turned into segments. Its segments keep it
 * (as their `source`) for as long as they are queued.
 *
 * A class rather than an object literal, like every object that lives with a queued
 * segment: V8 may "pretenure" an object literal whose objects all survive a young
 * collection (as they do while the queue fills), and then creates them in the old
 * generation, where each keeps the young objects it points at alive until the next
 * full collection. Class instances carry no such allocation site.
 */
export class ValidatedMove {
  readonly end: number[];
  readonly maxVelocity: number;
  readonly events: ResolvedEventSpec[];
  readonly maxAcceleration: number;

  constructor(end: number[], maxVelocity: number, events: ResolvedEventSpec[], maxAcceleration = Infinity) {
    this.end = end;
    this.maxVelocity = maxVelocity;
    this.events = events;
    this.maxAcceleration = maxAcceleration;
  }
}

/** The fractions of a move that is not subdivided. */
const WHOLE = [0, 1];

/** Lengths below this (mm) are treated as zero: such moves are skipped and counted. */
export const ZERO_LENGTH_MM = 1e-9;

function finite(field: string, value: unknown): number {
  if (typeof value !== 'number' || !Number.isFinite(value)) {
    throw new MaxlError('MOVE_INVALID', `must be a finite number, got ${String(value)}`, field);
  }
  return value;
}

/**
 * Checks a move against the config and the position it starts from. Throws a
 * MaxlError (MOVE_INVALID, MOVE_DIMENSION or SOFT_LIMIT) and changes nothing on
 * bad input.
 */
export function validateMove(config: ResolvedConfig, move: Move, from: readonly number[]): ValidatedMove {
  if (move === null || typeof move !== 'object') throw new MaxlError('MOVE_INVALID', 'a move must be an object with an endPosition');
  if (isDwell(move)) throw new MaxlError('MOVE_INVALID', 'dwells are not carried yet', 'dwell_s');
  const axes = config.motionAxes;
  const target = move.endPosition;
  let end: number[];
  if (Array.isArray(target)) {
    if (target.length !== axes.length) {
      throw new MaxlError(
        'MOVE_DIMENSION',
        `has ${target.length} values but the machine has ${axes.length} motion axes (${axes.join(', ')})`,
        'endPosition',
      );
    }
    end = new Array<number>(axes.length);
    for (let i = 0; i < axes.length; i++) {
      const v = target[i];
      // The field name is only built on the error path: this runs once per move.
      end[i] = typeof v === 'number' && Number.isFinite(v) ? v : finite(`endPosition[${i}]`, v);
    }
  } else if (target !== null && typeof target === 'object') {
    end = [...from];
    for (const [name, v] of Object.entries(target)) {
      const i = axes.indexOf(name);
      if (i < 0) throw new MaxlError('MOVE_DIMENSION', `"${name}" is not a motion axis (${axes.join(', ')})`, 'endPosition');
      end[i] = finite(`endPosition.${name}`, v);
    }
  } else {
    throw new MaxlError('MOVE_INVALID', 'must be an array of positions or an object of axis positions', 'endPosition');
  }
  for (let i = 0; i < axes.length; i++) {
    if (end[i] < config.softMin[i] || end[i] > config.softMax[i]) {
      throw new MaxlError(
        'SOFT_LIMIT',
        `${axes[i]} = ${end[i]} mm is outside the soft limits [${config.softMin[i]}, ${config.softMax[i]}] mm`,
        `endPosition.${axes[i]}`,
      );
    }
  }
  let maxVelocity = Infinity;
  if (move.maxVelocity !== undefined) {
    maxVelocity = finite('maxVelocity', move.maxVelocity);
    if (maxVelocity <= 0) throw new MaxlError('MOVE_INVALID', 'must be positive (mm/s)', 'maxVelocity');
  }
  let maxAcceleration = Infinity;
  if (move.maxAcceleration !== undefined) {
    maxAcceleration = finite('maxAcceleration', move.maxAcceleration);
    if (maxAcceleration <= 0) throw new MaxlError('MOVE_INVALID', 'must be positive (mm/s²)', 'maxAcceleration');
  }
  return new ValidatedMove(end, maxVelocity, resolveMoveEvents(move.eventChannels, config.eventChannels), maxAcceleration);
}

export function distance(a: readonly number[], b: readonly number[]): number {
  let d2 = 0;
  for (let i = 0; i < a.length; i++) {
    const d = b[i] - a[i];
    d2 += d * d;
  }
  return Math.sqrt(d2);
}

function hasNonlinearTransform(config: ResolvedConfig): boolean {
  for (const t of config.transforms) if (!t.linear) return true;
  return false;
}

/** What the next segment needs to know of the one before it. */
export interface PathTail {
  position: number[];
  /** Unit direction of the last segment, or null after rest with no segment. */
  unit: number[] | null;
  cruise2: number;
}

/**
 * The cruise cap (speed², mm²/s²) of a segment of `length` mm that must last at
 * least `minDuration_s` (a link's floor: net/linkFeedLimit.ts). A segment whose
 * speed never exceeds L/T lasts at least T: its duration is L over its mean speed,
 * and the mean is at most the maximum. Entry and exit speeds are capped by the
 * cruise cap too (the planner's maxEntry2 and the next segment's), so the cap
 * bounds the whole profile.
 */
export function floorCruise2(cruise2: number, length: number, minDuration_s: number): number {
  if (!(minDuration_s > 0)) return cruise2;
  const v = length / minDuration_s;
  return Math.min(cruise2, v * v);
}

/**
 * Splits a validated move into segments (one, unless a nonlinear transform needs
 * more), each with its planner inputs, numbered from firstId. Returns [] for a
 * zero-length move. With `minDuration_s`, each segment's speed is capped so that
 * it lasts at least that long (floorCruise2).
 */
export function segmentsForMove(
  config: ResolvedConfig,
  move: ValidatedMove,
  tail: PathTail,
  firstId: number,
  moveId: number,
  minDuration_s = 0,
): Segment[] {
  const p0 = tail.position;
  const total = distance(p0, move.end);
  if (total < ZERO_LENGTH_MM) return [];
  const unit = new Array<number>(p0.length);
  for (let i = 0; i < p0.length; i++) unit[i] = (move.end[i] - p0[i]) / total;
  const limits = config.limits;
  const speed = Math.min(move.maxVelocity, projectLimit(limits.maxSpeed, limits.axisMaxSpeed, unit));
  const moveCruise2 = speed * speed;
  const accel = Math.min(move.maxAcceleration, projectLimit(limits.maxAccel, limits.axisMaxAccel, unit));

  // Pieces of the move: one, unless a nonlinear transform needs more.
  const fractions = hasNonlinearTransform(config) ? subdivisionFractions(config.transforms, p0, move.end) : WHOLE;
  const segments = new Array<Segment>(fractions.length - 1);
  let prevUnit = tail.unit;
  let prevCruise2 = tail.cruise2;
  let start = p0;
  let a0 = actuatorPosition(config.transforms, p0);
  for (let k = 0; k + 1 < fractions.length; k++) {
    const last = k + 2 === fractions.length;
    const f1 = fractions[k + 1];
    const end = last ? move.end : p0.map((v, i) => v + (move.end[i] - v) * f1);
    const length = (f1 - fractions[k]) * total;
    const cruise2 = floorCruise2(moveCruise2, length, minDuration_s);
    const a1 = actuatorPosition(config.transforms, end);
    // Within one move all pieces share the direction; only the first meets a corner.
    const junction2 = prevUnit === null ? 0 : k === 0 ? junctionSpeed2(prevUnit, unit, limits) : Infinity;
    const maxEntry2 = Math.min(junction2, cruise2, prevUnit === null ? 0 : prevCruise2);
    let rate = a0; // (empty when there are no transforms)
    if (a0.length > 0) {
      rate = new Array<number>(a0.length);
      for (let j = 0; j < a0.length; j++) rate[j] = (a1[j] - a0[j]) / length;
    }
    const seg = new Segment(firstId + k, moveId, start, end, unit, length, fractions[k] * total, move);
    seg.actuatorStart = a0;
    seg.actuatorRate = rate;
    seg.accel = accel;
    seg.cruise2 = cruise2;
    seg.maxEntry2 = maxEntry2;
    segments[k] = seg;
    prevUnit = unit;
    prevCruise2 = cruise2;
    start = end;
    a0 = a1;
  }
  return segments;
}
