/**
 * Segments for a job resumed after the machine stopped off its plan (a link lost,
 * a device rebooted, a HALT, a refused segment): the rest of the segment each
 * reader stopped in, and fresh copies of the segments that were transmitted but
 * never ran. Copies are new, untimed segments with the same geometry, limits and
 * junction caps (the path is the same, so its corners are too); only their ids
 * and timing are new.
 */
import type { ResolvedConfig } from '../config/types.ts';
import { actuatorPosition } from '../config/transforms.ts';
import { Segment } from './segment.ts';

/**
 * Less of a segment than this (mm) is not resumed: the wire's position unit is
 * 2⁻¹⁶ mm, and a step is ~0.01 mm, so the next segment starts from the stop point.
 */
export const MIN_RESUME_MM = 1e-3;

/** A point of the path: `distance` mm along `segment`. */
export interface PathPoint {
  segment: Segment;
  distance: number;
}

/** The motion-space position of a path point. */
export function pointPosition(p: PathPoint): number[] {
  return p.segment.start.map((x, i) => x + p.segment.unit[i] * p.distance);
}

/** The actuator-space position of a path point (affine along a segment: segment.ts). */
export function pointActuators(p: PathPoint): number[] {
  const s = p.segment;
  return s.actuatorStart.map((x, j) => x + s.actuatorRate[j] * p.distance);
}

/** An untimed copy of `seg` under a new id. */
export function copySegment(seg: Segment, id: number): Segment {
  const copy = new Segment(id, seg.moveId, seg.start, seg.end, seg.unit, seg.length, seg.moveOffset, seg.source, seg.dwell_s);
  copyLimits(seg, copy);
  copy.maxEntry2 = seg.maxEntry2;
  return copy;
}

/**
 * The part of `p.segment` after `p.distance`, starting from rest; null if nothing
 * of it is left (within `minLength` mm). For a dwell (length 0) `distance` is the
 * fraction of it that ran: one that did not finish runs again whole, its events set
 * again at its start.
 */
export function remainderOf(p: PathPoint, id: number, minLength = MIN_RESUME_MM): Segment | null {
  const seg = p.segment;
  if (seg.isDwell) return p.distance < 1 ? copySegment(seg, id) : null;
  const length = seg.length - p.distance;
  if (!(length > minLength)) return null;
  const start = pointPosition(p);
  const piece = new Segment(id, seg.moveId, start, seg.end, seg.unit, length, seg.moveOffset + p.distance, seg.source);
  copyLimits(seg, piece);
  piece.actuatorStart = pointActuators(p);
  piece.maxEntry2 = 0;
  return piece;
}

/**
 * A straight segment from `from` to `to` (motion space), at the limits of the
 * segment it leads into: boards that stopped apart rejoin the path on it. Its
 * actuator rate is the chord's (exact for linear transforms; a rejoin is short).
 */
export function rejoinSegment(config: ResolvedConfig, from: number[], to: PathPoint, id: number): Segment {
  const end = pointPosition(to);
  const delta = end.map((x, i) => x - from[i]);
  const length = Math.hypot(...delta);
  const unit = delta.map((d) => d / length);
  // Move id 0 (no move has it): the rejoin belongs to no move, and is not part of one when found again (net/recovery.ts).
  const piece = new Segment(id, 0, from, end, unit, length, 0, to.segment.source);
  copyLimits(to.segment, piece);
  const a0 = actuatorPosition(config.transforms, from);
  const a1 = pointActuators(to);
  piece.actuatorStart = a0;
  piece.actuatorRate = a1.map((a, j) => (a - a0[j]) / length);
  piece.maxEntry2 = 0;
  return piece;
}

function copyLimits(from: Segment, to: Segment): void {
  to.actuatorStart = from.actuatorStart;
  to.actuatorRate = from.actuatorRate;
  to.accel = from.accel;
  to.cruise2 = from.cruise2;
}
