/**
 * Tracks: the trajectory read at a time t. Every track is a view of the same
 * segments (geometry × timing):
 *   motion axis i      start[i] + unit[i]·s(t)
 *   actuator axis j    actuatorStart[j] + actuatorRate[j]·s(t)
 *   velocity           s′(t), the speed along the path (mm/s)
 *   acceleration       s″(t), the acceleration along the path (mm/s²)
 *   event channel c    the last value set at or before t
 * Before the first segment the machine rests at its start; after the last it rests
 * at its end.
 */
import { evaluateTiming, timingDuration, type PathState, type Timing } from '../plan/phases.ts';

export interface TimedSegment {
  start: readonly number[];
  end: readonly number[];
  unit: readonly number[];
  actuatorStart: readonly number[];
  actuatorRate: readonly number[];
  timing: Timing | null;
}

export interface TrajectorySample {
  /** mm per motion axis */
  position: number[];
  /** mm per actuator axis */
  actuator: number[];
  /** mm/s per motion axis */
  velocity: number[];
  /** mm/s² per motion axis */
  acceleration: number[];
  /** mm/s along the path: the velocity track */
  speed: number;
  /** mm/s² along the path: the acceleration track */
  pathAcceleration: number;
  /** mm along the current segment */
  distance: number;
  /** index of the segment sampled in the list given, or −1 if none */
  index: number;
}

const scratch: PathState = { s: 0, v: 0, a: 0 };

/** Samples one timed segment at time `t` seconds after it began (clamped to the segment). */
export function sampleSegment(seg: TimedSegment, t: number, index = -1): TrajectorySample {
  const path = seg.timing ? evaluateTiming(seg.timing, t, scratch) : { s: 0, v: 0, a: 0 };
  return {
    position: seg.start.map((p, i) => p + seg.unit[i] * path.s),
    actuator: seg.actuatorStart.map((p, j) => p + seg.actuatorRate[j] * path.s),
    velocity: seg.unit.map((u) => u * path.v),
    acceleration: seg.unit.map((u) => u * path.a),
    speed: path.v,
    pathAcceleration: path.a,
    distance: path.s,
    index,
  };
}

/** The machine at rest at a point. */
export function restingSample(position: readonly number[], actuator: readonly number[], index = -1): TrajectorySample {
  return {
    position: [...position],
    actuator: [...actuator],
    velocity: position.map(() => 0),
    acceleration: position.map(() => 0),
    speed: 0,
    pathAcceleration: 0,
    distance: 0,
    index,
  };
}

/**
 * Index in [first, end) of the last segment starting at or before t, by binary
 * search over start times (ascending); −1 if t is before segment `first`.
 */
export function segmentIndexAt(first: number, end: number, startOf: (i: number) => number, t: number): number {
  let lo = first;
  let hi = end - 1;
  let found = -1;
  while (lo <= hi) {
    const mid = (lo + hi) >> 1;
    if (startOf(mid) <= t) {
      found = mid;
      lo = mid + 1;
    } else {
      hi = mid - 1;
    }
  }
  return found;
}

/**
 * Samples segments first … end−1 at time t: segmentAt(i) gives segment i and
 * startOf(i) its start, in the same unit as t; `toSeconds` converts a difference of
 * that unit to seconds. Only the segment sampled is fetched.
 */
export function sampleTimeline(
  first: number,
  end: number,
  segmentAt: (i: number) => TimedSegment,
  startOf: (i: number) => number,
  t: number,
  toSeconds: number,
): TrajectorySample | null {
  if (end <= first) return null;
  const i = segmentIndexAt(first, end, startOf, t);
  if (i < 0) {
    const seg = segmentAt(first);
    return restingSample(seg.start, seg.actuatorStart, -1);
  }
  const seg = segmentAt(i);
  const local = (t - startOf(i)) * toSeconds;
  const duration = seg.timing ? timingDuration(seg.timing) : 0;
  if (local >= duration && i === end - 1) {
    const endActuator = seg.actuatorStart.map((p, j) => p + seg.actuatorRate[j] * lengthOf(seg));
    return restingSample(seg.end, endActuator, i);
  }
  return sampleSegment(seg, local, i);
}

function lengthOf(seg: TimedSegment): number {
  let d2 = 0;
  for (let i = 0; i < seg.start.length; i++) d2 += (seg.end[i] - seg.start[i]) ** 2;
  return Math.sqrt(d2);
}
