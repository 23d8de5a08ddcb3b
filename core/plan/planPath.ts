/**
 * planPath: the pure planning entry point. It plans a whole polyline at once,
 * with the same code the queue uses (the segments of moves.ts and the lookahead of
 * lookahead.ts), starting at rest at `start` and ending at rest at the last move's
 * end.
 */
import { resolveLimits } from '../config/limits.ts';
import type { LimitsConfig, ResolvedConfig } from '../config/types.ts';
import { MaxlError } from '../errors.ts';
import { phasesOf, timingDuration, type Phase } from './phases.ts';
import { LookaheadPlanner } from './lookahead.ts';
import { segmentsForMove, validateMove, type PathTail } from '../trajectory/moves.ts';
import { sampleTimeline, type TrajectorySample } from '../trajectory/tracks.ts';
import type { Segment } from '../trajectory/segment.ts';

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
  /** mm/s, the cap the planner had for this segment (limits and the move's maxVelocity) */
  cruiseLimit: number;
  /** mm/s², the acceleration limit along the segment */
  accelerationLimit: number;
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

export interface PathMove {
  end: number[];
  maxVelocity?: number;
}

export function planPath(start: number[], moves: PathMove[], limits: LimitsConfig): PlannedPath {
  if (!Array.isArray(start) || start.length === 0) throw new MaxlError('MOVE_DIMENSION', 'must be a non-empty array of positions', 'start');
  start.forEach((v, i) => {
    if (typeof v !== 'number' || !Number.isFinite(v)) throw new MaxlError('MOVE_INVALID', `must be a finite number, got ${String(v)}`, `start[${i}]`);
  });
  if (!Array.isArray(moves)) throw new MaxlError('MOVE_INVALID', 'must be an array of { end, maxVelocity? }', 'moves');
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
      const v = validateMove(config, { endPosition: m?.end, maxVelocity: m?.maxVelocity }, from);
      from = v.end;
      return v;
    } catch (err) {
      if (err instanceof MaxlError) throw new MaxlError(err.code, err.message, `moves[${i}]`);
      throw err;
    }
  });

  const planner = new LookaheadPlanner<Segment>();
  const segments: Segment[] = [];
  let tail: PathTail = { position: [...start], unit: null, cruise2: 0 };
  let skipped = 0;
  validated.forEach((move, moveId) => {
    const segs = segmentsForMove(config, move, tail, segments.length, moveId);
    if (segs.length === 0) skipped++;
    for (const seg of segs) {
      planner.append(seg);
      segments.push(seg);
      tail = { position: seg.end, unit: seg.unit, cruise2: seg.cruise2 };
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
      accelerationLimit: seg.accel,
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
      const s: TrajectorySample | null = sampleTimeline(0, segments.length, (i) => segments[i], startOf, time, 1);
      if (s === null) return { ...atStart, position: [...start] };
      return { position: s.position, velocity: s.velocity, acceleration: s.acceleration };
    },
  };
}
