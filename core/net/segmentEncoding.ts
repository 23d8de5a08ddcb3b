/**
 * Author-side encoding of timed segments for one device (docs/protocol.md §4-§5):
 * GEOMETRY carries each segment's length and the end value of each position track
 * the device reads; TIMING carries its phases in the device's own clock.
 *
 * Times are converted boundary by boundary: every phase boundary's author time is
 * mapped through the device's clock model and rounded to a whole µs, and durations
 * are differences of those rounded boundaries. Consecutive segments therefore stay
 * exactly contiguous on the device, whatever the rounding.
 *
 * σ(t) is normalised (0 … 1 along the segment), so TIMING sends alpha = a/L and
 * not the entry speed: the device recovers it from σ(T) = 1 (§5).
 */
import { PHASE_STRIDE, type Timing } from '../plan/phases.ts';
import type { ClockMap } from './clockMap.ts';
import type { GeometrySegment, MessageOf, TimingSegment } from './messages.ts';
import { HAS_P0, HAS_START, MAX_PAYLOAD, PhaseShape, POSITION_SCALE } from './protocol.ts';

/** What encoding needs of a segment: geometry, timing and its author start time. */
export interface EncodableSegment {
  length: number;
  start: readonly number[];
  end: readonly number[];
  actuatorStart: readonly number[];
  actuatorRate: readonly number[];
  timing: Timing | null;
  startTime_us: number;
}

/** A position track as a device reads it: a motion axis or an actuator axis, by index. */
export interface PositionSlot {
  space: 'motion' | 'actuator';
  index: number;
}

export function positionAt(seg: EncodableSegment, slot: PositionSlot, atEnd: boolean): number {
  if (slot.space === 'motion') return atEnd ? seg.end[slot.index] : seg.start[slot.index];
  return seg.actuatorStart[slot.index] + (atEnd ? seg.actuatorRate[slot.index] * seg.length : 0);
}

/** A position in 2⁻¹⁶ units, as an i32. */
export function toWirePosition(value: number): number {
  const q = Math.round(value * POSITION_SCALE);
  if (q > 0x7fffffff || q < -0x80000000) throw new RangeError(`position ${value} is outside the wire's ±32 767 range`);
  return q;
}

const GEOMETRY_HEADER = 4;
const TIMING_HEADER = 8;

/**
 * GEOMETRY messages for consecutive segments with wire ids from firstId, as many
 * per message as fit. With `withP0`, the first message also says where each slot
 * starts.
 */
export function geometryMessages(
  segments: readonly EncodableSegment[],
  slots: readonly PositionSlot[],
  firstId: number,
  withP0: boolean,
  /** Where each slot starts, if not at the first segment's start (a board resuming from where it stopped). */
  p0Values?: readonly number[],
): MessageOf<'GEOMETRY'>[] {
  const out: MessageOf<'GEOMETRY'>[] = [];
  const perSegment = 4 + 4 * slots.length;
  let i = 0;
  while (i < segments.length) {
    const p0 = withP0 && out.length === 0;
    const room = Math.floor((MAX_PAYLOAD - GEOMETRY_HEADER - (p0 ? 4 * slots.length : 0)) / perSegment);
    const batch = segments.slice(i, i + Math.min(room, 255));
    const geometry: GeometrySegment[] = batch.map((seg) => ({ length: seg.length, p1: slots.map((s) => toWirePosition(positionAt(seg, s, true))) }));
    const message: MessageOf<'GEOMETRY'> = { type: 'GEOMETRY', firstId: (firstId + i) & 0xffff, count: batch.length, flags: p0 ? HAS_P0 : 0, segments: geometry };
    if (p0) message.p0 = p0Values ? p0Values.map(toWirePosition) : slots.map((s) => toWirePosition(positionAt(segments[0], s, false)));
    out.push(message);
    i += batch.length;
  }
  return out;
}

function varintSize(v: number): number {
  let n = 1;
  while (v >= 0x80) {
    v = Math.floor(v / 128);
    n++;
  }
  return n;
}

/** At most this fraction of a cruise phase absorbs a clock-model correction. */
export const MAX_CRUISE_CORRECTION = 0.005;

/**
 * One segment's TIMING entry in the device's clock, its device start (u32), and
 * its end as an exact (unrounded, unwrapped) device time.
 *
 * After rest (no `chainFrom`), the start comes from the clock model. A segment
 * that continues the device's timed path starts exactly where the previous one
 * ended (`chainFrom`, exact), and its phases last their author durations times
 * the model's rate: the profile's shape is never distorted, which matters most
 * for a phase accelerating from rest, whose entry speed the device derives from
 * σ(end) = 1. Where the model has moved since (it is refitted every second), the
 * difference is absorbed a little at a time in cruise phases only. Boundaries are
 * rounded from the exact chain, so rounding never builds up.
 *
 * How much a cruise phase may absorb. The device knows only α and the durations,
 * and solves ν0 = (1 − α·Q)/T from σ(T) = 1 (protocol §5). Stretching a cruise at
 * speed v_c by `take` µs adds v_c·take to the distance, so the device lowers every
 * speed of the segment by the same δv = v_c·take/T (mm/s, T its µs), its entry and
 * exit speeds included; shrinking raises them. A segment that starts or ends at
 * rest would then start or end at −δv, which the device refuses as MALFORMED
 * (it allows only what whole-µs rounding explains), or at +δv, a jump from rest.
 * So the change is capped at MAX_CRUISE_CORRECTION of the lower end speed:
 *   |δv| ≤ MAX·min(v_e, v_x)  ⇔  |take| ≤ MAX·T·min(v_e, v_x)/v_c,
 * and at MAX_CRUISE_CORRECTION of the cruise itself. A segment at rest at an end
 * takes none; what is left is carried to the next one (it is recomputed from the
 * model each time). A dwell (length 0) moves nothing, so its whole hold absorbs
 * up to MAX_CRUISE_CORRECTION with no speed changing.
 */
export function timingEntry(seg: EncodableSegment, clock: ClockMap, chainFrom?: number): { entry: TimingSegment; start: number; end: number } {
  const timing = seg.timing;
  if (timing === null) throw new Error('timingEntry: segment is not timed');
  const phases = timing.length / PHASE_STRIDE;
  const modelStart = clock.toDeviceExact(seg.startTime_us);
  let error = chainFrom === undefined ? 0 : modelStart - chainFrom;
  let exact = chainFrom ?? modelStart;
  const boundaries = [Math.round(exact)];
  let shape = 0;
  let accel = 0;
  const endSpeedShare = error === 0 ? 0 : cruiseCorrectionShare(seg.length, timing);
  for (let k = 0; k < phases; k++) {
    const o = k * PHASE_STRIDE;
    let duration = timing[o + 1] * 1e6 * clock.rate;
    const a = timing[o + 4];
    if (a === 0 && error !== 0) {
      // room = MAX·min(cruise, T·min(v_e, v_x)/v_c), in device µs (see above)
      const room = Math.min(duration, endSpeedShare * clock.rate * 1e6 / Math.max(timing[o + 3], Number.MIN_VALUE)) * MAX_CRUISE_CORRECTION;
      const take = Math.max(-room, Math.min(room, error));
      duration += take;
      error -= take;
    }
    exact += duration;
    boundaries.push(Math.round(exact));
    shape |= (a > 0 ? PhaseShape.accelerate : a < 0 ? PhaseShape.decelerate : PhaseShape.cruise) << (2 * k);
    if (a !== 0) accel = Math.abs(a);
  }
  const durations = boundaries.slice(1).map((b, k) => b - boundaries[k]);
  // d²σ/dt_dev² = (a/L)·(dt_author/dt_dev)²
  const alpha = seg.length > 0 ? accel / seg.length / (clock.rate * clock.rate) : 0;
  const start = ((boundaries[0] % 0x1_0000_0000) + 0x1_0000_0000) % 0x1_0000_0000;
  return { entry: { shape, durations, alpha }, start, end: exact };
}

/**
 * T·min(v_e, v_x) of a segment (author s · mm/s): how far its cruise phases may be
 * stretched or shrunk, divided by MAX_CRUISE_CORRECTION and their speed (timingEntry).
 * Infinite for a dwell, whose hold moves nothing.
 */
function cruiseCorrectionShare(length: number, timing: Timing): number {
  if (length === 0) return Infinity;
  const o = timing.length - PHASE_STRIDE;
  const entry = timing[3];
  const exit = timing[o + 3] + timing[o + 4] * timing[o + 1];
  return (timing[o] + timing[o + 1]) * Math.max(0, Math.min(entry, exit));
}

/**
 * TIMING messages for consecutive, contiguous timed segments. The first carries its
 * start when `withStart` (after rest, or first of a session), never before `startAt`;
 * otherwise it follows the device's timed path, which ends at `startAt` (exact,
 * unwrapped device µs).
 * The exact device end of the last one is returned in `end`. `stopDecel` (mm/s², in author
 * time) is how hard a device brakes along provisional geometry if no more timing
 * follows a message's last segment.
 */
export function timingMessages(
  segments: readonly EncodableSegment[],
  clock: ClockMap,
  firstId: number,
  withStart: boolean,
  stopDecel: number,
  startAt?: number,
): MessageOf<'TIMING'>[] & { end?: number; spans: Array<{ start: number; length: number }> } {
  const out: MessageOf<'TIMING'>[] & { end?: number; spans: Array<{ start: number; length: number }> } = Object.assign([], { spans: [] });
  let current: MessageOf<'TIMING'> | null = null;
  let size = 0;
  let chain = withStart ? undefined : startAt;
  segments.forEach((seg, i) => {
    // After rest, a run starts where the clock model puts its author start, but never
    // before the device's timed path ends: the model may have moved back since that
    // path was sent, and a start even 1 µs before its end overlaps it, which the device
    // refuses (MALFORMED). The path ended at rest, so starting a little later is safe.
    const fromRest = startAt !== undefined && clock.toDeviceExact(seg.startTime_us) < startAt ? startAt : undefined;
    const from = chain ?? fromRest;
    const { entry, start, end } = timingEntry(seg, clock, from);
    // Where the segment lies on the device's timeline: exact start, and its length in whole µs.
    const exactStart = from ?? clock.toDeviceExact(seg.startTime_us);
    out.spans.push({ start: exactStart, length: entry.durations.reduce((a, b) => a + b, 0) });
    chain = end;
    out.end = end;
    const entrySize = 1 + entry.durations.reduce((n, d) => n + varintSize(d), 0) + 4;
    const needStart = withStart && i === 0;
    if (current === null || size + entrySize > MAX_PAYLOAD || current.count === 255) {
      // The device brakes in its own time: a_dev = a·(dt_author/dt_dev)².
      const decel = stopDecel / (clock.rate * clock.rate);
      current = { type: 'TIMING', firstId: (firstId + i) & 0xffff, count: 0, flags: needStart ? HAS_START : 0, stopDecel: decel, segments: [] };
      if (needStart) current.start = start;
      size = TIMING_HEADER + (needStart ? 4 : 0);
      out.push(current);
    }
    current.segments.push(entry);
    current.count++;
    size += entrySize;
  });
  return out;
}
