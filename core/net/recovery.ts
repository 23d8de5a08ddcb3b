/**
 * Where a job resumes after the machine stopped off its plan (docs/architecture.md,
 * "Recovery"). Each board that reads the trajectory says where it stopped: a STATUS
 * naming a segment by wire id and σ along it. A board that restarted knows nothing;
 * its motors stopped dead, on the path, where the plan had them when it was last
 * heard from (an estimate, off by up to the speed times the time between frames).
 *
 * The path in order is what went out on the wire (the streamer's log) followed by
 * what was never transmitted. Boards that reached different points resume from the
 * one furthest back; the others rejoin it along a short straight segment first.
 */
import { evaluateTiming } from '../plan/phases.ts';
import type { Segment } from '../trajectory/segment.ts';
import { MIN_RESUME_MM, pointActuators, pointPosition, type PathPoint } from '../trajectory/restart.ts';
import type { MessageOf } from './messages.ts';
import { positionAt, type PositionSlot } from './segmentEncoding.ts';

/** Where one board stopped, and how the author knows. */
export interface BoardStop {
  device: string;
  point: PathPoint;
  /** 'status': the board said so; 'estimate': it restarted, and the plan at its last frame says so. */
  source: 'status' | 'estimate';
}

/** The path in order, as far as recovery can see it: what went out on the wire, then the untransmitted rest. */
export function pathInOrder(sentInOrder: readonly Segment[], untransmitted: readonly Segment[]): Segment[] {
  const seen = new Set<Segment>();
  const out: Segment[] = [];
  for (const seg of sentInOrder) {
    if (seg.locked && !seen.has(seg)) {
      seen.add(seg);
      out.push(seg);
    }
  }
  for (const seg of untransmitted) if (!seen.has(seg)) out.push(seg);
  return out;
}

/** A board's STATUS as a path point (σ along the segment it names); null if that segment is unknown. */
export function pointFromStatus(status: MessageOf<'STATUS'>, segmentForWireId: (id: number) => Segment | undefined): PathPoint | null {
  const segment = segmentForWireId(status.segmentId);
  if (!segment) return null;
  const sigma = Math.min(1, Math.max(0, status.sigma));
  return { segment, distance: segment.isDwell ? sigma : segment.length * sigma };
}

/**
 * The same point on a segment of `path`. A board may have stopped on geometry the
 * author has since cut into slices (a long segment is locked a slice at a time):
 * the point is found again by its move and its distance along that move.
 */
export function onPath(path: readonly Segment[], p: PathPoint): PathPoint {
  if (path.includes(p.segment) || p.segment.moveId === 0) return p;
  if (p.segment.isDwell) {
    const same = path.find((s) => s.moveId === p.segment.moveId && s.isDwell);
    return same ? { segment: same, distance: p.distance } : p;
  }
  const along = p.segment.moveOffset + p.distance;
  const tolerance = 1e-6;
  const seg = path.find((s) => s.moveId === p.segment.moveId && !s.isDwell && s.moveOffset - tolerance <= along && along <= s.moveOffset + s.length + tolerance);
  return seg ? { segment: seg, distance: Math.min(seg.length, Math.max(0, along - seg.moveOffset)) } : p;
}

/** Where the plan had the machine at author time t, on the transmitted path (null if nothing was transmitted). */
export function pointAtTime(path: readonly Segment[], t_us: number): PathPoint | null {
  let last: Segment | null = null;
  for (const seg of path) {
    if (!seg.locked || !seg.timing) continue;
    if (t_us < seg.startTime_us) break;
    last = seg;
    if (t_us < seg.endTime_us) {
      const s = evaluateTiming(seg.timing, (t_us - seg.startTime_us) * 1e-6, { s: 0, v: 0, a: 0 }).s;
      return { segment: seg, distance: seg.isDwell ? (t_us - seg.startTime_us) / (seg.duration_s * 1e6) : Math.min(seg.length, Math.max(0, s)) };
    }
  }
  return last ? { segment: last, distance: last.isDwell ? 1 : last.length } : null;
}

/** The plan for resuming: from where, what runs again, and each board's own starting values. */
export interface ResumePlan {
  /** The point the path resumes from: the stop furthest back. */
  from: PathPoint;
  /** Transmitted segments after it that never ran. */
  rerun: Segment[];
  /** The furthest point a board reached, when boards stopped apart by more than MIN_RESUME_MM; else null. */
  rejoinFrom: number[] | null;
  /** mm between the furthest and the hindmost stop. */
  spread_mm: number;
}

/** Orders the boards' stops along `path` and plans the resume (null if no board said anything usable). */
export function planResume(path: readonly Segment[], stops: readonly BoardStop[]): ResumePlan | null {
  if (stops.length === 0) return null;
  const rank = (p: PathPoint) => {
    const i = path.indexOf(p.segment);
    return (i < 0 ? path.length : i) + (p.segment.isDwell ? p.distance : p.distance / Math.max(p.segment.length, 1e-12)) * 0.999;
  };
  const sorted = [...stops].sort((a, b) => rank(a.point) - rank(b.point));
  const from = sorted[0].point;
  const furthest = sorted[sorted.length - 1].point;
  const a = pointPosition(from);
  const b = pointPosition(furthest);
  const spread_mm = Math.hypot(...a.map((x, i) => x - b[i]));
  const index = path.indexOf(from.segment);
  const rerun = index < 0 ? [] : path.slice(index + 1).filter((s) => s.locked);
  return { from, rerun, rejoinFrom: spread_mm > MIN_RESUME_MM ? b : null, spread_mm };
}

/** Each position slot's value at a path point: where a board that stopped there stands. */
export function slotValuesAt(p: PathPoint, slots: readonly PositionSlot[]): number[] {
  const position = pointPosition(p);
  const actuators = pointActuators(p);
  return slots.map((s) => positionAt({ length: 0, start: position, end: position, actuatorStart: actuators, actuatorRate: actuators.map(() => 0), timing: null, startTime_us: NaN }, s, false));
}
