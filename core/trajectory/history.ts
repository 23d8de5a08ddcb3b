/**
 * The as-planned history: every transmitted segment's geometry and timing, kept in
 * one Float64Array ring rather than as objects, so that a long job's history costs
 * neither allocation nor garbage-collector time, and sampling the past stays a
 * binary search.
 *
 * One record per segment, `stride` doubles:
 *   [0] start, author µs        [1] duration, s       [2] length, mm
 *   [3] timing length           [4 …] the packed timing, room for MAX_PHASES phases
 *   then start[A], unit[A], actuatorStart[B], actuatorRate[B], eventsAtStart[E]
 * with A motion axes, B actuator axes and E event channels. Event changes inside a
 * segment (rare: only where a move sets channels) are kept beside it, by record.
 */
import { PHASE_STRIDE, writeTrapezoidOf, type Timing, type TrapezoidInputs } from '../plan/phases.ts';
import type { EventTrack } from './events.ts';
import type { Segment } from './segment.ts';
import { sampleTimeline, segmentIndexAt, type TimedSegment, type TrajectorySample } from './tracks.ts';

/** Trapezoids have up to 3 phases; S-curves will need 7. */
export const MAX_PHASES = 3;
const HEADER = 4;

/** The scalar fields and actuators of a record, as a transmitted segment has them. */
export interface HistoryRecordFields {
  startTime_us: number;
  duration_s: number;
  length: number;
  actuatorStart: readonly number[];
  actuatorRate: readonly number[];
  eventsAtStart: readonly number[] | null;
}

/**
 * A line segment as an executor locks it without making it an object (the queue's
 * columnar front): its trapezoid's inputs, its start time (author µs) and its
 * geometry, as fields of an object the executor reuses.
 */
export interface LockedLine extends TrapezoidInputs {
  startTime_us: number;
  start: ArrayLike<number>;
  unit: ArrayLike<number>;
  actuatorStart: readonly number[];
  actuatorRate: readonly number[];
}

export interface HistoricalSegment extends TimedSegment {
  startTime_us: number;
  duration_s: number;
  length: number;
  timing: Timing;
  eventsAtStart: number[];
  eventTracks: readonly EventTrack[];
}

/**
 * Copies packed phases to d from offset o, a whole phase (its six numbers, t0 …
 * jerk) per step: a million segments a second go through here, and a loop per
 * number costs twice as much.
 */
function copyPhases(d: Float64Array, o: number, timing: ArrayLike<number>, length: number): void {
  for (let k = 0; k < length; k += PHASE_STRIDE) {
    d[o + k] = timing[k];
    d[o + k + 1] = timing[k + 1];
    d[o + k + 2] = timing[k + 2];
    d[o + k + 3] = timing[k + 3];
    d[o + k + 4] = timing[k + 4];
    d[o + k + 5] = timing[k + 5];
  }
}

/** Writes a[0 … n) then b[0 … n) (a point and its rate along s) to d from offset o; returns the offset after them. */
function copyPair(d: Float64Array, o: number, a: ArrayLike<number>, b: ArrayLike<number>, n: number): number {
  for (let i = 0; i < n; i++) {
    d[o + i] = a[i];
    d[o + n + i] = b[i];
  }
  return o + 2 * n;
}

export class TrajectoryHistory {
  readonly capacity: number;
  private readonly axes: number;
  private readonly actuators: number;
  private readonly channels: number;
  private readonly stride: number;
  /** Grows by doubling up to capacity records, so a short job does not commit the whole ring. */
  private data: Float64Array;
  /** Records pushed so far; record n lives at slot n % capacity while n ≥ count − capacity. */
  private count = 0;
  /** count % capacity, kept by push() rather than divided out for every record. */
  private nextSlot = 0;
  private readonly events = new Map<number, readonly EventTrack[]>();

  constructor(axes: number, actuators: number, channels: number, capacity: number) {
    this.axes = axes;
    this.actuators = actuators;
    this.channels = channels;
    this.capacity = Math.max(1, Math.floor(capacity));
    this.stride = HEADER + MAX_PHASES * PHASE_STRIDE + 2 * axes + 2 * actuators + channels;
    this.data = new Float64Array(Math.min(this.capacity, 1024) * this.stride);
  }

  /**
   * Author µs before which the history no longer knows the plan: the start of the oldest
   * record kept once older ones were dropped to make room; −∞ while nothing was dropped.
   */
  get horizon_us(): number {
    return this.count > this.capacity ? this.startOf(0) : -Infinity;
  }

  /** Records pushed since the history was made (kept or dropped). */
  get pushed(): number {
    return this.count;
  }

  /** Records held (at most `capacity`). */
  get size(): number {
    return Math.min(this.count, this.capacity);
  }

  /** Copies a transmitted segment in; the oldest record goes when the ring is full. */
  push(seg: Segment): void {
    const timing = seg.timing;
    if (timing === null) throw new Error(`history: segment ${seg.id} has no timing`);
    this.pushRecord(seg, timing, timing.length, seg.start, seg.unit, seg.eventTracks);
  }

  /**
   * Copies a transmitted segment in from its parts, for a segment never made into
   * an object (the queue's columnar tail, locked by a dry run): `timing` holds
   * `timingLength` packed numbers; `seg` gives the scalar fields and actuators.
   */
  pushRecord(
    seg: HistoryRecordFields,
    timing: ArrayLike<number>,
    timingLength: number,
    start: ArrayLike<number>,
    unit: ArrayLike<number>,
    eventTracks: readonly EventTrack[] | null,
  ): void {
    if (timingLength > MAX_PHASES * PHASE_STRIDE) throw new Error(`history: a segment of ${timingLength / PHASE_STRIDE} phases (at most ${MAX_PHASES})`);
    const o = this.nextRecord(eventTracks);
    copyPhases(this.data, o + HEADER, timing, timingLength);
    this.writeFields(o, seg.startTime_us, seg.duration_s, seg.length, timingLength, start, unit, seg.actuatorStart, seg.actuatorRate, seg.eventsAtStart);
  }

  /**
   * Records a transmitted line segment timed by the trapezoid of plan/phases.ts, its
   * phases written by writeTrapezoidOf straight into the ring (a dry run locks a
   * million segments a second: no copy through a buffer, and its numbers read from
   * the fields of `line`, not passed one by one), and returns its duration (s) as
   * timingDuration() gives it: the last phase's start plus its length.
   */
  pushLine(line: LockedLine, eventsAtStart: readonly number[] | null): number {
    const o = this.nextRecord(null);
    const d = this.data;
    const n = writeTrapezoidOf(d, o + HEADER, line) * PHASE_STRIDE;
    const last = o + HEADER + n - PHASE_STRIDE;
    const duration_s = d[last] + d[last + 1];
    this.writeFields(o, line.startTime_us, duration_s, line.length, n, line.start, line.unit, line.actuatorStart, line.actuatorRate, eventsAtStart);
    return duration_s;
  }

  /** Takes the next record's slot (dropping the oldest record when the ring is full) and returns its offset in `data`. */
  private nextRecord(eventTracks: readonly EventTrack[] | null): number {
    const n = this.count++;
    if (n < this.capacity) this.makeRoomFor(n);
    else if (this.events.size > 0) this.events.delete(n - this.capacity); // its slot is reused now
    const o = this.nextSlot * this.stride;
    this.nextSlot = this.nextSlot + 1 === this.capacity ? 0 : this.nextSlot + 1;
    if (eventTracks && eventTracks.length > 0) this.events.set(n, eventTracks);
    return o;
  }

  /** Writes a record's fields but its phases, at offset o. */
  private writeFields(
    o: number,
    startTime_us: number,
    duration_s: number,
    length: number,
    timingLength: number,
    start: ArrayLike<number>,
    unit: ArrayLike<number>,
    actuatorStart: readonly number[],
    actuatorRate: readonly number[],
    atStart: readonly number[] | null,
  ): void {
    const d = this.data;
    d[o] = startTime_us;
    d[o + 1] = duration_s;
    d[o + 2] = length;
    d[o + 3] = timingLength;
    let v = o + HEADER + MAX_PHASES * PHASE_STRIDE;
    v = copyPair(d, v, start, unit, this.axes);
    v = copyPair(d, v, actuatorStart, actuatorRate, this.actuators);
    for (let c = 0; c < this.channels; c++) d[v + c] = atStart ? atStart[c] : 0;
  }

  /** Grows the ring (doubling, up to capacity) so that it has a slot for record n < capacity. */
  private makeRoomFor(n: number): void {
    if ((n + 1) * this.stride <= this.data.length) return;
    const grown = new Float64Array(Math.min(this.capacity, 2 * (n + 1)) * this.stride);
    grown.set(this.data);
    this.data = grown;
  }

  /** The i-th record held, 0 the oldest, rebuilt as plain objects. */
  at(i: number): HistoricalSegment {
    const n = this.count - this.size + i;
    const d = this.data;
    let o = (n % this.capacity) * this.stride;
    const timing = Array.from(d.subarray(o + HEADER, o + HEADER + d[o + 3]));
    const startTime_us = d[o];
    const duration_s = d[o + 1];
    const length = d[o + 2];
    o += HEADER + MAX_PHASES * PHASE_STRIDE;
    const take = (k: number) => Array.from(d.subarray(o, (o += k)));
    const start = take(this.axes);
    const unit = take(this.axes);
    const actuatorStart = take(this.actuators);
    const actuatorRate = take(this.actuators);
    const eventsAtStart = take(this.channels);
    return {
      startTime_us,
      duration_s,
      length,
      timing,
      start,
      unit,
      end: start.map((p, a) => p + unit[a] * length),
      actuatorStart,
      actuatorRate,
      eventsAtStart,
      eventTracks: this.events.get(n) ?? [],
    };
  }

  private startOf = (i: number): number => this.data[((this.count - this.size + i) % this.capacity) * this.stride];

  /** Index of the record running at t_us (the last to start at or before it), or −1. */
  indexAt(t_us: number): number {
    return segmentIndexAt(0, this.size, this.startOf, t_us);
  }

  /** Every track at author time t_us, or null if the history is empty. */
  sample(t_us: number): TrajectorySample | null {
    return sampleTimeline(0, this.size, (i) => this.at(i), this.startOf, t_us, 1e-6);
  }

  /** An event channel's value at t_us: the last value set at or before it (0 before the history). */
  eventValue(channel: number, t_us: number): number {
    const i = this.indexAt(t_us);
    if (i < 0) return 0;
    const rec = this.at(i);
    let value = rec.eventsAtStart[channel];
    const local = (t_us - rec.startTime_us) * 1e-6;
    for (const track of rec.eventTracks) {
      if (track.channel !== channel) continue;
      for (let k = 0; k < track.times.length && track.times[k] <= local; k++) value = track.values[k];
    }
    return value;
  }
}
