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
 */
import { resolveLimits } from '../config/limits.ts';
import type { LimitsConfig, ResolvedConfig } from '../config/types.ts';
import { MaxlError } from '../errors.ts';
import { phasesOf, timingDuration, type Phase } from '../plan/phases.ts';
import { LookaheadPlanner } from '../plan/lookahead.ts';
import { segmentsForMove, tailAfter, validateMove, type Move, type PathTail } from './moves.ts';
import { sampleTimeline, type TrajectorySample } from './tracks.ts';
import type { Segment } from './segment.ts';

export interface PlannedSegment {
  start: number[];
  end: number[];
  /** mm */
  length: number;
  /** s since the path began */
  startTime: number;
  /** s */
  duration: number;
  /** mm/s */
  entryVelocity: number;
  exitVelocity: number;
  /** mm/s, the highest speed reached inside the segment */
  peakVelocity: number;
  /** mm/s, the cap the planner had for this segment (limits, the move's maxVelocity, the link's floor; 0 for a dwell) */
  cruiseLimit: number;
  /** mm/s², the acceleration limit along the segment (0 for a dwell, which has no direction) */
  accelerationLimit: number;
  /** Whether this is a dwell: start = end, length 0, speed 0 throughout, lasting `duration`. */
  dwell: boolean;
  phases: Phase[];
}

export interface PathSample {
  position: number[];
  velocity: number[];
  acceleration: number[];
}

export interface PlannedPath {
  /** s */
  duration: number;
  segments: PlannedSegment[];
  /** Zero-length moves skipped. */
  skipped: number;
  /** The state at t seconds after the start (clamped: at rest before 0 and after `duration`). */
  sample(t: number): PathSample;
}

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
  // Validate everything first: bad input throws before any planning.
  let from = start;
  const validated = moves.map((m, i) => {
    try {
      // A dwell that also gives `end` or `maxVelocity` is refused by validateMove, as in the queue.
      const line = m as Partial<PathLine> | undefined;
      const move: Move =
        m !== null && typeof m === 'object' && 'dwell_s' in m
          ? ({ dwell_s: m.dwell_s, endPosition: line?.end, maxVelocity: line?.maxVelocity } as Move)
          : { endPosition: line?.end as number[], maxVelocity: line?.maxVelocity };
      const v = validateMove(config, move, from);
      from = v.end;
      return v;
    } catch (err) {
      // The queue's words name `endPosition`; a path move's key is `end`.
      if (err instanceof MaxlError) {
        const field = (err.field ?? '').replace(/^endPosition/, 'end');
        throw new MaxlError(err.code, err.message.split('endPosition').join('end'), `moves[${i}]${field ? `.${field}` : ''}`);
      }
      throw err;
    }
  });

  const planner = new LookaheadPlanner<Segment>();
  const segments: Segment[] = [];
  const tail: PathTail = { position: [...start], unit: null, cruise2: 0 };
  let skipped = 0;
  validated.forEach((move, moveId) => {
    const segs = segmentsForMove(config, move, tail, segments.length, moveId, floor_us * 1e-6);
    if (segs.length === 0) skipped++;
    for (const seg of segs) {
      planner.append(seg);
      segments.push(seg);
      tailAfter(seg, tail);
    }
  });
  planner.planToRest();

  const planned: PlannedSegment[] = [];
  let t = 0;
  for (const seg of segments) {
    const phases = phasesOf(seg.time());
    const duration = timingDuration(seg.timing!);
    planned.push({
      start: seg.start,
      end: seg.end,
      length: seg.length,
      startTime: t,
      duration,
      entryVelocity: Math.sqrt(seg.entry2),
      exitVelocity: Math.sqrt(seg.exit2),
      peakVelocity: Math.max(...phases.map((p) => p.v0 + p.a0 * p.duration), ...phases.map((p) => p.v0)),
      cruiseLimit: Math.sqrt(seg.cruise2),
      accelerationLimit: seg.isDwell ? 0 : seg.accel,
      dwell: seg.isDwell,
      phases,
    });
    t += duration;
  }
  const startOf = (i: number) => planned[i].startTime;
  const atStart: PathSample = { position: [...start], velocity: start.map(() => 0), acceleration: start.map(() => 0) };
  return {
    duration: t,
    segments: planned,
    skipped,
    sample(time: number): PathSample {
      if (typeof time !== 'number' || Number.isNaN(time)) throw new MaxlError('MOVE_INVALID', `must be a time in s, got ${String(time)}`, 't');
      const s: TrajectorySample | null = sampleTimeline(0, segments.length, (i) => segments[i], startOf, time, 1);
      if (s === null) return { ...atStart, position: [...start] };
      return { position: s.position, velocity: s.velocity, acceleration: s.acceleration };
    },
  };
}
