/**
 * From a move request (an end position, a speed cap, event values; or a dwell) to
 * segments: validation, soft limits, zero-length skipping, subdivision for nonlinear
 * transforms, and each segment's planner inputs (limits projected on its direction,
 * the junction cap with the segment before).
 *
 * A dwell is one segment of length 0 that holds its position at rest for its
 * duration: start = end, a zero direction, entry and exit caps 0 (the planner
 * brings the machine to rest before it and starts from rest after it), and one
 * phase of speed 0 lasting `dwell_s`. A zero-length move that sets events is an
 * event-only move: a dwell of 0 s, so that its events happen; one that sets none
 * is skipped, as before.
 */
import { MaxlError } from '../errors.ts';
import { LIMIT_RANGE, projectLimit, type ResolvedLimits } from '../config/limits.ts';
import type { ResolvedConfig } from '../config/types.ts';
import { junctionSpeed2 } from '../plan/junction.ts';
import { resolveMoveEvents, type MoveEvents } from './events.ts';
import { Segment } from './segment.ts';
import { ValidatedMove } from './validatedMove.ts';
import { actuatorPosition, subdivisionFractions } from '../config/transforms.ts';

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

export { ValidatedMove };

export function isDwell(move: Move): move is DwellMove {
  return move !== null && typeof move === 'object' && 'dwell_s' in move;
}

/**
 * The longest dwell, s. The wire times a segment in whole device µs and refuses a
 * total of 2³¹ µs (2 147 s) or more, which would not compare wrap-safely
 * (docs/protocol.md §4 TIMING); 2 000 s leaves room for the clock model's rate and
 * its corrections. A longer wait is several dwells.
 */
export const MAX_DWELL_S = 2000;

/** The fractions of a move that is not subdivided. */
const WHOLE = [0, 1];

/**
 * How far from 0 a position track may go, mm. Positions travel as i32 in 2⁻¹⁶ mm
 * (docs/protocol.md), so the wire carries ±32 768 mm; the author keeps a margin.
 */
export const TRACK_POSITION_LIMIT_MM = 32_767;

/**
 * Refuses an end position that a reader could not be sent: a motion axis, or an
 * actuator after the transforms (a CoreXY sum can pass the range inside valid
 * soft limits), beyond the wire's range. Actuators are linear between the ends of
 * a segment of a linear transform, so checking the ends covers the whole segment.
 * The transforms run here too, so a function transform that throws or gives a
 * non-number is refused before anything is queued; the actuators it returns are
 * kept with the move, so making its last segment does not compute them again.
 */
function checkTrackRange(config: ResolvedConfig, end: readonly number[], motionChecked: boolean): number[] {
  const axes = config.motionAxes;
  for (let i = 0; i < axes.length && !motionChecked; i++) {
    if (Math.abs(end[i]) > TRACK_POSITION_LIMIT_MM) {
      throw new MaxlError('MOVE_INVALID', `${axes[i]} = ${end[i]} mm is beyond the ±${TRACK_POSITION_LIMIT_MM} mm a position track can carry`, `endPosition.${axes[i]}`);
    }
  }
  const actuators = actuatorPosition(config.transforms, end);
  for (let j = 0; j < actuators.length; j++) {
    if (Math.abs(actuators[j]) > TRACK_POSITION_LIMIT_MM) {
      throw new MaxlError(
        'MOVE_INVALID',
        `actuator ${config.actuatorAxes[j]} would be at ${actuators[j]} mm, beyond the ±${TRACK_POSITION_LIMIT_MM} mm a position track can carry`,
        'endPosition',
      );
    }
  }
  return actuators;
}

/**
 * The slowest speed cap a move may ask for, mm/s (1 µm/s). Below it, a speed's
 * square underflows towards 0 (1e-300² is 0 in float64) and a segment's duration
 * outgrows what the wire can time.
 */
export const MIN_SPEED = LIMIT_RANGE.speed[0];
/** The gentlest acceleration cap a move may ask for, mm/s²: as the machine limits (config/limits.ts). */
export const MIN_ACCELERATION = LIMIT_RANGE.accel[0];

/**
 * With devices (the runtime sets it with the links' floor, core/runtime.ts), every
 * segment of length > 0 lasts at least this long (s), whatever the links allow:
 * TIMING carries whole µs, and a segment timed 0 µs for a length > 0 is one the
 * reader refuses (it cannot cover distance in no time). Boundaries round by at most
 * ½ µs each, so 2 µs never rounds to 0. Only a segment under 2 µs (a few nm at any
 * speed a machine runs) is slowed by it.
 */
export const WIRE_MIN_SEGMENT_S = 2e-6;

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
  if (move === null || typeof move !== 'object') throw new MaxlError('MOVE_INVALID', 'a move must be an object with an endPosition, or a dwell with dwell_s');
  if (isDwell(move)) return validateDwell(config, move, from);
  const axes = config.motionAxes;
  const target = move.endPosition;
  let end: number[];
  // Whether every motion axis is known to be within the soft limits and the track range already.
  let inRange = false;
  if (Array.isArray(target)) {
    if (target.length !== axes.length) {
      throw new MaxlError(
        'MOVE_DIMENSION',
        `has ${target.length} values but the machine has ${axes.length} motion axes (${axes.join(', ')})`,
        'endPosition',
      );
    }
    // One pass for the common move, every value a number within the soft limits and the
    // track range (so finite); any other goes through the checks below, in their order.
    end = new Array<number>(axes.length);
    const { softMin, softMax } = config;
    inRange = true;
    for (let i = 0; i < axes.length; i++) {
      const v = target[i];
      if (typeof v === 'number' && v >= softMin[i] && v <= softMax[i] && Math.abs(v) <= TRACK_POSITION_LIMIT_MM) {
        end[i] = v;
        continue;
      }
      inRange = false;
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
  for (let i = 0; i < axes.length && !inRange; i++) {
    if (end[i] < config.softMin[i] || end[i] > config.softMax[i]) {
      throw new MaxlError(
        'SOFT_LIMIT',
        `${axes[i]} = ${end[i]} mm is outside the soft limits [${config.softMin[i]}, ${config.softMax[i]}] mm`,
        `endPosition.${axes[i]}`,
      );
    }
  }
  const actuatorEnd = checkTrackRange(config, end, inRange);
  let maxVelocity = Infinity;
  if (move.maxVelocity !== undefined) {
    maxVelocity = finite('maxVelocity', move.maxVelocity);
    if (!(maxVelocity >= MIN_SPEED)) throw new MaxlError('MOVE_INVALID', `must be at least ${MIN_SPEED} mm/s, got ${maxVelocity}`, 'maxVelocity');
  }
  let maxAcceleration = Infinity;
  if (move.maxAcceleration !== undefined) {
    maxAcceleration = finite('maxAcceleration', move.maxAcceleration);
    if (!(maxAcceleration >= MIN_ACCELERATION)) throw new MaxlError('MOVE_INVALID', `must be at least ${MIN_ACCELERATION} mm/s², got ${maxAcceleration}`, 'maxAcceleration');
  }
  return new ValidatedMove(end, maxVelocity, resolveMoveEvents(move.eventChannels, config.eventChannels), null, maxAcceleration, actuatorEnd);
}

/**
 * Whether `target` is an end position validateMove takes as it is: an array of one
 * number per motion axis, each within the soft limits and the track range (so
 * finite). validateMove's end is then a copy of it, and its actuators the shared
 * empty array on a machine without transforms. For batch callers that skip making
 * the ValidatedMove of every plain move; any other goes through validateMove, which
 * decides (and may refuse).
 */
export function isPlainEnd(config: ResolvedConfig, target: unknown): target is number[] {
  if (!Array.isArray(target)) return false;
  const n = config.motionAxes.length;
  if (target.length !== n) return false;
  const { softMin, softMax } = config;
  for (let i = 0; i < n; i++) {
    const v: unknown = target[i];
    if (!(typeof v === 'number' && v >= softMin[i] && v <= softMax[i] && Math.abs(v) <= TRACK_POSITION_LIMIT_MM)) return false;
  }
  return true;
}

/** Whether a move's optional cap (maxVelocity with MIN_SPEED, maxAcceleration with MIN_ACCELERATION) is absent or one validateMove takes as it is. */
export function isPlainCap(value: unknown, min: number): boolean {
  return value === undefined || (typeof value === 'number' && value >= min && value < Infinity);
}

/**
 * Whether validateMove(config, move) would return, without refusing it, a linear
 * move with end = a copy of move.endPosition, the move's caps (Infinity when absent),
 * no event (NO_SPECS) and no actuators (NO_ACTUATORS): a LinearMove that sets no
 * event, with a plain end (isPlainEnd) and plain caps, on a machine without
 * transforms.
 */
export function isPlainLine(config: ResolvedConfig, move: Move): move is LinearMove & { endPosition: number[] } {
  if (config.transforms.length > 0 || move === null || typeof move !== 'object' || 'dwell_s' in move) return false;
  return (
    move.eventChannels === undefined &&
    isPlainCap(move.maxVelocity, MIN_SPEED) &&
    isPlainCap(move.maxAcceleration, MIN_ACCELERATION) &&
    isPlainEnd(config, move.endPosition)
  );
}

/** A dwell holds wherever the path is: it takes no end position and no speed, and lasts 0 to MAX_DWELL_S s. */
function validateDwell(config: ResolvedConfig, move: DwellMove, from: readonly number[]): ValidatedMove {
  for (const field of ['endPosition', 'maxVelocity', 'maxAcceleration'] as const) {
    if ((move as Partial<LinearMove>)[field] !== undefined) {
      throw new MaxlError('MOVE_INVALID', `a dwell holds its position at rest: it takes no ${field} (give a linear move, then the dwell)`, field);
    }
  }
  const dwell_s = finite('dwell_s', move.dwell_s);
  if (dwell_s < 0) throw new MaxlError('MOVE_INVALID', `must be ≥ 0 s, got ${dwell_s}`, 'dwell_s');
  if (dwell_s > MAX_DWELL_S) throw new MaxlError('MOVE_INVALID', `must be at most ${MAX_DWELL_S} s (what the wire times in one segment); chain dwells for longer`, 'dwell_s');
  return new ValidatedMove([...from], 0, resolveMoveEvents(move.eventChannels, config.eventChannels), dwell_s);
}

/**
 * The acceleration limit a dwell's segment carries. A dwell has no direction and
 * covers no distance, so it never limits anything (2·a·0 = 0 in the planner); the
 * value only has to be finite and positive for code that divides by it. The
 * machine's weakest finite limit is both.
 */
export function dwellAccel(config: ResolvedConfig): number {
  let a = config.limits.maxAccel;
  for (const v of config.limits.axisMaxAccel) if (v < a) a = v;
  return a;
}

/** The one segment of a dwell of `dwell_s` s at `position`, from rest to rest. */
function dwellSegment(config: ResolvedConfig, move: ValidatedMove, position: number[], dwell_s: number, id: number, moveId: number): Segment {
  const zero = new Array<number>(position.length).fill(0);
  const seg = new Segment(id, moveId, position, position, zero, 0, 0, move, dwell_s);
  const actuators = actuatorPosition(config.transforms, position);
  seg.actuatorStart = actuators;
  seg.actuatorRate = actuators.length > 0 ? actuators.map(() => 0) : actuators;
  seg.accel = dwellAccel(config);
  seg.cruise2 = 0;
  seg.maxEntry2 = 0;
  return seg;
}

export function distance(a: readonly number[], b: readonly number[]): number {
  let d2 = 0;
  for (let i = 0; i < a.length; i++) {
    const d = b[i] - a[i];
    d2 += d * d;
  }
  return Math.sqrt(d2);
}

/** d(actuator)/ds along a straight piece from actuators a0 to a1 over `length` mm. */
export function actuatorRate(a0: readonly number[], a1: readonly number[], length: number): number[] {
  const rate = new Array<number>(a0.length);
  for (let j = 0; j < a0.length; j++) rate[j] = (a1[j] - a0[j]) / length;
  return rate;
}

/** Writes the unit direction from p0 to p1 into `unit` and returns the distance (mm); `unit` is not meaningful below ZERO_LENGTH_MM. */
export function directionInto(p0: readonly number[], p1: readonly number[], unit: number[]): number {
  const total = distance(p0, p1);
  for (let i = 0; i < p0.length; i++) unit[i] = (p1[i] - p0[i]) / total;
  return total;
}

export function hasNonlinearTransform(config: ResolvedConfig): boolean {
  for (const t of config.transforms) if (!t.linear) return true;
  return false;
}

/** What the next segment needs to know of the one before it. */
export interface PathTail {
  position: number[];
  /** Unit direction of the last segment, or null after rest (no segment yet, or a dwell). */
  unit: number[] | null;
  cruise2: number;
}

/** The path's tail after `seg`: a dwell leaves the machine at rest, so the next segment starts from rest. */
export function tailAfter(seg: Segment, tail: PathTail): void {
  tail.position = seg.end;
  tail.unit = seg.isDwell ? null : seg.unit;
  tail.cruise2 = seg.isDwell ? 0 : seg.cruise2;
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

/** The speed² cap (mm²/s²) of a line along `unit`: the move's own cap and the machine's speed limits projected on it. */
export function lineCruise2(limits: ResolvedLimits, move: ValidatedMove, unit: readonly number[]): number {
  const speed = Math.min(move.maxVelocity, projectLimit(limits.maxSpeed, limits.axisMaxSpeed, unit));
  return speed * speed;
}

/** The acceleration limit (mm/s²) of a line along `unit`: the move's own cap and the machine's limits projected on it. */
export function lineAccel(limits: ResolvedLimits, move: ValidatedMove, unit: readonly number[]): number {
  return Math.min(move.maxAcceleration, projectLimit(limits.maxAccel, limits.axisMaxAccel, unit));
}

/**
 * The cap on a line's entry speed² (mm²/s²) after a tail leaving along `prevUnit`
 * (null: at rest) with cruise cap `prevCruise2`: the corner's junction speed (none
 * when `corner` is false: a piece continuing its own move straight on), this line's
 * cruise cap and the one before.
 */
export function entryCap2(limits: ResolvedLimits, prevUnit: readonly number[] | null, prevCruise2: number, unit: readonly number[], cruise2: number, corner: boolean): number {
  if (prevUnit === null) return 0;
  const junction2 = corner ? junctionSpeed2(prevUnit, unit, limits) : Infinity;
  return Math.min(junction2, cruise2, prevCruise2);
}

/**
 * Splits a validated move into segments (one, unless a nonlinear transform needs
 * more), each with its planner inputs, numbered from firstId. A dwell is one
 * segment at the tail's position; so is a zero-length move that sets events (a
 * dwell of 0 s). Returns [] for a zero-length move that sets none. With
 * `minDuration_s`, each segment's speed is capped so that it lasts at least that
 * long (floorCruise2); a dwell lasts its own time.
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
  if (move.dwell_s !== null) return [dwellSegment(config, move, p0, move.dwell_s, firstId, moveId)];
  const unit = new Array<number>(p0.length);
  const total = directionInto(p0, move.end, unit);
  if (total < ZERO_LENGTH_MM) return move.events.length > 0 ? [dwellSegment(config, move, p0, 0, firstId, moveId)] : [];
  const limits = config.limits;
  const moveCruise2 = lineCruise2(limits, move, unit);
  const accel = lineAccel(limits, move, unit);

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
    const a1 = last && move.actuatorEnd !== null ? move.actuatorEnd : actuatorPosition(config.transforms, end);
    // Within one move all pieces share the direction; only the first meets a corner.
    const maxEntry2 = entryCap2(limits, prevUnit, prevCruise2, unit, cruise2, k === 0);
    const rate = a0.length > 0 ? actuatorRate(a0, a1, length) : a0; // (empty when there are no transforms)
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
