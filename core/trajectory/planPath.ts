/**
 * planPath: the pure planning entry point. It plans a whole polyline at once,
 * with the same code the queue uses (the segments of moves.ts and the lookahead of
 * lookahead.ts), starting at rest at `start` and ending at rest at the last move's
 * end. Dwells (`{ dwell_s }`) hold the position at rest; the plan comes to rest
 * before each and starts from rest after it, as the queue's does.
 *
 * With `minSegment_us` (a link's floor, net/linkFeedLimit.ts: pass `maxl.feedLimit`)
 * every line segment is capped to last at least that long, exactly as the queue
 * caps the segments it is given on that link (moves.ts floorCruise2), so the
 * planned duration is the time the queue will run.
 *
 * It computes each move's planner inputs with the queue's own functions (lineLimits.ts,
 * moves.ts: the same arithmetic, so the same plan to the last bit) but makes no Segment
 * objects: the inputs go straight into the planner's typed-array store, and the
 * result is columnar (plannedPath.ts). One pass validates, plans and times; a bad
 * move throws before anything is returned.
 */
import { resolveLimits } from '../config/limits.ts';
import type { LimitsConfig, ResolvedConfig } from '../config/types.ts';
import { MaxlError, ownMessage } from '../errors.ts';
import { trapezoidDuration } from '../plan/phases.ts';
import { LookaheadPlanner } from '../plan/lookahead.ts';
import { ColumnarPlannedPath, PathColumns, type PlannedPath } from './plannedPath.ts';
import { dwellAccel, floorCruise2, isPlainCap, isPlainEnd, MIN_SPEED, validateMove, ZERO_LENGTH_MM, type Move, type ValidatedMove } from './moves.ts';
import { LineLimits } from './lineLimits.ts';

export type { PathSample, PlannedPath, PlannedSegment } from './plannedPath.ts';

/** A straight move to `end`, at most `maxVelocity` mm/s. */
export interface PathLine {
  end: number[];
  maxVelocity?: number;
}

/** Hold the position at rest for `dwell_s` s. */
export interface PathDwell {
  dwell_s: number;
}

export type PathMove = PathLine | PathDwell;

export interface PlanPathOptions {
  /**
   * µs: the floor on every line segment's duration that the queue applies on a slow
   * link (`maxl.feedLimit.minSegment_us`); 0 or absent for none.
   */
  minSegment_us?: number;
}

export function planPath(start: number[], moves: PathMove[], limits: LimitsConfig, options: PlanPathOptions = {}): PlannedPath {
  if (!Array.isArray(start) || start.length === 0) throw new MaxlError('MOVE_DIMENSION', 'must be a non-empty array of positions', 'start');
  start.forEach((v, i) => {
    if (typeof v !== 'number' || !Number.isFinite(v)) throw new MaxlError('MOVE_INVALID', `must be a finite number, got ${String(v)}`, `start[${i}]`);
  });
  if (!Array.isArray(moves)) throw new MaxlError('MOVE_INVALID', 'must be an array of { end, maxVelocity? } or { dwell_s }', 'moves');
  const floor_us = options.minSegment_us ?? 0;
  if (typeof floor_us !== 'number' || !(floor_us >= 0) || !Number.isFinite(floor_us)) {
    throw new MaxlError('MOVE_INVALID', `must be a finite duration ≥ 0 µs, got ${String(floor_us)}`, 'options.minSegment_us');
  }
  const axes = start.map((_, i) => `axis${i}`);
  const config: ResolvedConfig = {
    motionAxes: axes,
    eventChannels: [],
    actuatorAxes: [],
    tracks: [],
    limits: resolveLimits(limits, axes.length),
    transforms: [],
    subscriptions: [],
    softMin: axes.map(() => -Infinity),
    softMax: axes.map(() => Infinity),
    queueCapacity: Infinity,
  };
  const axisCount = start.length;
  const lineLimits = new LineLimits(config.limits);
  const minDuration_s = floor_us * 1e-6;
  const columns = new PathColumns(axisCount, moves.length, start);
  const vertices = columns.vertices;
  // Each block is locked as soon as its plan is final (locking a final block changes no
  // plan: lookahead.ts), so the planner holds only the blocks within braking distance of
  // the path's end, in a ring that stays small and in cache, whatever the path's length.
  // A final plan is reported by offset from the front, which is row `locked`; its row's
  // duration is timed at once, while the row's inputs are still in cache.
  let locked = 0;
  const planner: LookaheadPlanner = new LookaheadPlanner(0, (offset) => {
    const row = locked + offset;
    const entry2 = planner.finalEntry2(offset);
    const exit2 = planner.finalExit2(offset);
    columns.entry2s[row] = entry2;
    columns.exit2s[row] = exit2;
    // (A dwell's duration is its own, written when it was appended.)
    if (columns.dwells[row] !== 1) columns.durations[row] = trapezoidDuration(columns.lengths[row], entry2, exit2, columns.cruise2s[row], columns.accels[row]);
  });
  // The tail of the path: the last line's direction and cruise cap (null after rest), in two
  // alternating buffers so that a new direction never overwrites the one it is compared with.
  let unit = new Array<number>(axisCount).fill(0);
  let prevUnit: number[] | null = null;
  let spare = new Array<number>(axisCount).fill(0);
  let prevCruise2 = 0;
  let from: readonly number[] = start;
  let skipped = 0;
  let n = 0;
  const restAccel = dwellAccel(config);
  for (let i = 0; i < moves.length; i++) {
    const m = moves[i];
    // A plain line (an `end` and at most a valid maxVelocity) is what validateMove would
    // return as it is, so its own fields serve; any other move is validated (and may be
    // refused) there.
    let end: readonly number[];
    let maxVelocity: number;
    let maxAcceleration = Infinity;
    let dwell_s: number | null = null;
    if (isPlainPathLine(config, m)) {
      end = m.end;
      maxVelocity = m.maxVelocity ?? Infinity;
    } else {
      const move = validatePathMove(config, m, from, i);
      end = move.end;
      maxVelocity = move.maxVelocity;
      maxAcceleration = move.maxAcceleration;
      dwell_s = move.dwell_s;
    }
    from = end;
    if (dwell_s !== null) {
      // A dwell: length 0, entry and exit caps 0 (moves.ts dwellSegment).
      columns.dwells[n] = 1;
      columns.durations[n] = dwell_s;
      columns.accels[n] = restAccel;
      planner.append(0, restAccel, 0);
      prevUnit = null;
      prevCruise2 = 0;
    } else {
      const row = n * axisCount;
      const total = lengthFrom(vertices, row, end);
      if (total < ZERO_LENGTH_MM) {
        skipped++;
        continue;
      }
      for (let a = 0; a < axisCount; a++) unit[a] = (end[a] - vertices[row + a]) / total;
      const cruise2 = floorCruise2(lineLimits.cruise2(maxVelocity, unit), total, minDuration_s);
      const accel = lineLimits.accel(maxAcceleration, unit);
      columns.lengths[n] = total;
      columns.cruise2s[n] = cruise2;
      columns.accels[n] = accel;
      planner.append(total, accel, lineLimits.entryCap2(prevUnit, prevCruise2, unit, cruise2));
      const used = unit;
      unit = spare;
      spare = used;
      prevUnit = used;
      prevCruise2 = cruise2;
    }
    // The segment ends at the move's end; a dwell holds where the path is.
    const next = (n + 1) * axisCount;
    if (dwell_s !== null) vertices.copyWithin(next, next - axisCount, next);
    else for (let a = 0; a < axisCount; a++) vertices[next + a] = end[a];
    n++;
    while (planner.plannedSize > 0) {
      planner.lockFront();
      locked++;
    }
  }
  planner.planToRest();
  columns.count = n;

  // The duration: each row's (timed as its plan became final) summed in path order, as
  // the start times are when first asked for (PathColumns.startTime).
  let t = 0;
  for (let i = 0; i < n; i++) t += columns.durations[i];
  return new ColumnarPlannedPath(columns, t, skipped);
}

/**
 * Whether path move `m` is a line that validatePathMove would return as it is: an
 * object that is not a dwell, with a plain `end` (moves.ts isPlainEnd: one number
 * per axis, within the track range) and, if any, a maxVelocity validateMove takes
 * unchanged. Its own fields then serve as the validated move's.
 */
function isPlainPathLine(config: ResolvedConfig, m: PathMove): m is PathLine {
  return m !== null && typeof m === 'object' && !('dwell_s' in m) && isPlainCap(m.maxVelocity, MIN_SPEED) && isPlainEnd(config, m.end);
}

/** mm from the vertex at vertices[row …] to `end`, as moves.ts distance() computes it. */
function lengthFrom(vertices: Float64Array, row: number, end: readonly number[]): number {
  let d2 = 0;
  for (let a = 0; a < end.length; a++) {
    const d = end[a] - vertices[row + a];
    d2 += d * d;
  }
  return Math.sqrt(d2);
}

/** Validates path move i as the queue validates a move, in a path move's words (`end`, `moves[i]`). */
function validatePathMove(config: ResolvedConfig, m: PathMove, from: readonly number[], i: number): ValidatedMove {
  try {
    // A dwell that also gives `end` or `maxVelocity` is refused by validateMove, as in the queue.
    const line = m as Partial<PathLine> | undefined;
    const move: Move =
      m !== null && typeof m === 'object' && 'dwell_s' in m
        ? ({ dwell_s: m.dwell_s, endPosition: line?.end, maxVelocity: line?.maxVelocity } as Move)
        : { endPosition: line?.end as number[], maxVelocity: line?.maxVelocity };
    return validateMove(config, move, from);
  } catch (err) {
    // The queue's words name `endPosition`; a path move's key is `end`.
    if (err instanceof MaxlError) {
      const field = (err.field ?? '').replace(/^endPosition/, 'end');
      throw new MaxlError(err.code, ownMessage(err).split('endPosition').join('end'), `moves[${i}]${field ? `.${field}` : ''}`);
    }
    throw err;
  }
}
