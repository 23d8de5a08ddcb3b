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
 * difference is absorbed a little at a time in cruise phases only, at most
 * MAX_CRUISE_CORRECTION of each, where stretching just changes the cruise speed by
 * as much. Boundaries are rounded from the exact chain, so rounding never builds up.
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
  for (let k = 0; k < phases; k++) {
    const o = k * PHASE_STRIDE;
    let duration = timing[o + 1] * 1e6 * clock.rate;
    const a = timing[o + 4];
    if (a === 0 && error !== 0) {
      const room = duration * MAX_CRUISE_CORRECTION;
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
 * TIMING messages for consecutive, contiguous timed segments. The first carries its
 * start when `withStart` (after rest, or first of a session); otherwise it follows
 * the device's timed path, which ends at `startAt` (exact, unwrapped device µs).
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
    const from = chain;
    const { entry, start, end } = timingEntry(seg, clock, chain);
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
