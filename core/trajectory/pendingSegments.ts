/**
 * The queue's columnar tail: untransmitted segments kept as numbers, not objects,
 * until someone needs them as `Segment`s.
 *
 * A queue that plans ahead holds hundreds to tens of thousands of untransmitted
 * segments (as deep as braking needs: queue.ts hasRoom). Kept as objects, each
 * (a Segment, its unit vector, its timing) outlives several young-generation
 * collections, which copy it, then promote it: a profile of the planner bench
 * found the collector at 12–30 % of the time. Kept here, a queued segment costs
 * one record of numbers (see RECORD_SCALARS below), allocated once, and three
 * references when it has events or actuators: its move's numbers (end position,
 * speed and acceleration caps) are copied into the record, so the validated move
 * and its end array die young, and only what is shared (the move's event specs) or
 * made by a transform (actuator positions) is referenced; a segment with neither
 * (the common case) stores no reference at all (HAS_REFS). The validated move is
 * made again, equal, when the object is.
 *
 * The store holds one kind of segment only, the common one: a linear move that
 * became a single segment (no nonlinear transform subdividing it), not a dwell.
 * Its moveOffset is 0, its end is its move's end, and its move has no other
 * segment (so the move made again for it is not shared with another segment). The queue (queue.ts) makes a `Segment` of a slot when it is
 * transmitted (takeFront), and turns the whole store into objects (takeAll) before
 * anything else reads or edits the untransmitted path: a listener, the read-only
 * view, an edit, a split, a restart. The object it makes is the one the queue
 * keeps from then on, so a segment's identity never changes.
 *
 * Slots form a ring: entry i (0 = the oldest) lives at slot (head + i) & mask, and
 * the ring doubles when full.
 */
import { NO_SPECS, type ResolvedEventSpec } from './events.ts';
import { NO_ACTUATORS } from '../config/transforms.ts';
import type { LockedLine } from './history.ts';
import { actuatorRate } from './moves.ts';
import { Segment } from './segment.ts';
import { ValidatedMove } from './validatedMove.ts';

const INITIAL_CAPACITY = 1024;

/**
 * Where the store finds what the planner holds of the segments it holds (the
 * lookahead planner, plan/lookahead.ts): their inputs (length, acceleration limit,
 * entry cap, as the queue appended them) and final plans, by offset from the
 * planner's front block, which is the store's oldest segment plus the object
 * segments held before it. Kept there only, not copied here too: at a deep
 * lookahead (thousands of segments) every column costs cache.
 */
export interface PlannerBlocks {
  lengthAt(offset: number): number;
  accelAt(offset: number): number;
  maxEntry2At(offset: number): number;
  isFinal(offset: number): boolean;
  finalEntry2(offset: number): number;
  finalExit2(offset: number): number;
}

/**
 * The oldest segment's fields, as readFront() copies them into an object its caller
 * reuses; the caller adds what locking it decides (LockedLine's start time, entry
 * and exit speeds², actuator rates) before it records the segment (history.ts).
 */
export interface PendingFront extends LockedLine {
  /** Written in place: as many numbers as motion axes. */
  start: number[];
  end: number[];
  unit: number[];
  events: readonly ResolvedEventSpec[];
  actuatorStart: number[];
  /** The move's actuators at its end (null only for a dwell, never held here). */
  actuatorEnd: number[] | null;
}

/**
 * A slot's numbers, side by side in one Float64Array (a record of RECORD_SCALARS + 3 ×
 * axes numbers), not one column per quantity: the executor reads the oldest slot,
 * which at a deep lookahead was written thousands of appends ago and is out of the
 * cache, and one record is one or two cache lines where a column each was eleven.
 */
const ID = 0;
const MOVE_ID = 1;
const CRUISE2 = 2;
/** The move's caps: mm/s and mm/s² (Infinity for the machine's limits). */
const MAX_VELOCITY = 3;
const MAX_ACCELERATION = 4;
/**
 * 1 when the slot's references are kept in the reference columns; 0 when they are
 * the shared empty arrays (no event, no actuator: NO_SPECS, NO_ACTUATORS at both
 * ends), the common case, for which the columns are not touched at all (three
 * stores, three reads and three clears of references fewer per segment).
 */
const HAS_REFS = 5;
/** Then the start position, the end position and the unit vector, `axes` numbers each. */
const RECORD_SCALARS = 6;

export class PendingSegments {
  private readonly axes: number;
  /** Numbers per slot. */
  private readonly stride: number;
  private mask = INITIAL_CAPACITY - 1;
  private head = 0;
  private count = 0;
  private records: Float64Array<ArrayBuffer>;
  private events: (readonly ResolvedEventSpec[] | undefined)[] = new Array(INITIAL_CAPACITY);
  private actuatorStarts: (number[] | undefined)[] = new Array(INITIAL_CAPACITY);
  private actuatorEnds: (number[] | null | undefined)[] = new Array(INITIAL_CAPACITY);

  constructor(axes: number) {
    this.axes = axes;
    this.stride = RECORD_SCALARS + 3 * axes;
    this.records = new Float64Array(INITIAL_CAPACITY * this.stride);
  }
  /** Segments held. */
  get size(): number {
    return this.count;
  }

  /**
   * Appends a single-segment linear move's segment at the end of the path: its id,
   * its move's id and fields (end position, copied; speed and acceleration caps,
   * mm/s and mm/s², Infinity for the machine's; event specs and actuators at the end,
   * by reference), where it starts and its unit direction (both copied), and its
   * cruise cap; its other planner inputs (length, acceleration, entry cap) are the
   * planner's block, appended with it. The actuators at its start are kept by
   * reference (the shared empty array without transforms).
   */
  push(
    id: number,
    moveId: number,
    end: readonly number[],
    maxVelocity: number,
    maxAcceleration: number,
    events: readonly ResolvedEventSpec[],
    actuatorEnd: number[] | null,
    start: readonly number[],
    unit: readonly number[],
    cruise2: number,
    actuatorStart: number[],
  ): void {
    if (this.count > this.mask) this.grow();
    const s = (this.head + this.count) & this.mask;
    this.count++;
    const r = this.records;
    const o = s * this.stride;
    r[o + ID] = id;
    r[o + MOVE_ID] = moveId;
    r[o + CRUISE2] = cruise2;
    r[o + MAX_VELOCITY] = maxVelocity;
    r[o + MAX_ACCELERATION] = maxAcceleration;
    const a = this.axes;
    const p = o + RECORD_SCALARS;
    for (let i = 0; i < a; i++) {
      r[p + i] = start[i];
      r[p + a + i] = end[i];
      r[p + 2 * a + i] = unit[i];
    }
    const shared = events === NO_SPECS && actuatorStart === NO_ACTUATORS && actuatorEnd === NO_ACTUATORS;
    r[o + HAS_REFS] = shared ? 0 : 1;
    if (shared) return;
    this.events[s] = events;
    this.actuatorStarts[s] = actuatorStart;
    this.actuatorEnds[s] = actuatorEnd;
  }

  /** Slot s's event specs (see HAS_REFS). */
  private eventsOf(s: number): readonly ResolvedEventSpec[] {
    return this.records[s * this.stride + HAS_REFS] === 0 ? NO_SPECS : (this.events[s] as readonly ResolvedEventSpec[]);
  }

  /** Slot s's actuators at its start (see HAS_REFS). */
  private actuatorStartOf(s: number): number[] {
    return this.records[s * this.stride + HAS_REFS] === 0 ? NO_ACTUATORS : (this.actuatorStarts[s] as number[]);
  }

  /** Slot s's move's actuators at its end (see HAS_REFS). */
  private actuatorEndOf(s: number): number[] | null {
    return this.records[s * this.stride + HAS_REFS] === 0 ? NO_ACTUATORS : (this.actuatorEnds[s] as number[] | null);
  }

  /**
   * Removes the oldest segment and returns it as a Segment, planned and timed if
   * its plan is final in `plans`, where it is the block `offset` places after the
   * front.
   */
  takeFront(plans: PlannerBlocks, offset: number): Segment {
    if (this.count === 0) throw new Error('PendingSegments.takeFront: empty');
    const seg = this.segmentAt(this.head, plans, offset);
    this.dropFront();
    return seg;
  }

  /**
   * Copies the oldest segment's fields into `out` (its start and unit in place),
   * without making an object; it must be the front block of `blocks` (no object
   * segment held before it), which gives its length and acceleration.
   */
  readFront(out: PendingFront, blocks: PlannerBlocks): PendingFront {
    if (this.count === 0) throw new Error('PendingSegments.readFront: empty');
    const s = this.head;
    const a = this.axes;
    const r = this.records;
    const o = s * this.stride;
    const p = o + RECORD_SCALARS;
    for (let i = 0; i < a; i++) {
      out.start[i] = r[p + i];
      out.end[i] = r[p + a + i];
      out.unit[i] = r[p + 2 * a + i];
    }
    out.events = this.eventsOf(s);
    out.actuatorStart = this.actuatorStartOf(s);
    out.actuatorEnd = this.actuatorEndOf(s);
    out.length = blocks.lengthAt(0);
    out.accel = blocks.accelAt(0);
    out.cruise2 = r[o + CRUISE2];
    return out;
  }

  /** Removes the oldest segment. */
  dropFront(): void {
    if (this.count === 0) throw new Error('PendingSegments.dropFront: empty');
    this.release(this.head);
    this.head = (this.head + 1) & this.mask;
    this.count--;
  }

  /** Removes every segment and returns them as Segments, in path order; the oldest is the block `offset` places after the front of `plans`. */
  takeAll(plans: PlannerBlocks, offset: number): Segment[] {
    const out = new Array<Segment>(this.count);
    for (let i = 0; i < out.length; i++) {
      const s = (this.head + i) & this.mask;
      out[i] = this.segmentAt(s, plans, offset + i);
      this.release(s);
    }
    this.head = 0;
    this.count = 0;
    return out;
  }

  /** The Segment of slot s, as segmentsForMove (moves.ts) would have made it, with its plan if final (block `offset` of `plans`). */
  private segmentAt(s: number, plans: PlannerBlocks, offset: number): Segment {
    const a = this.axes;
    const r = this.records;
    const o = s * this.stride;
    const p = o + RECORD_SCALARS;
    const start = Array.from(r.subarray(p, p + a));
    const end = Array.from(r.subarray(p + a, p + 2 * a));
    const unit = Array.from(r.subarray(p + 2 * a, p + 3 * a));
    const actuatorEnd = this.actuatorEndOf(s);
    const source = new ValidatedMove(end, r[o + MAX_VELOCITY], this.eventsOf(s) as ResolvedEventSpec[], null, r[o + MAX_ACCELERATION], actuatorEnd);
    const length = plans.lengthAt(offset);
    const seg = new Segment(r[o + ID], r[o + MOVE_ID], start, end, unit, length, 0, source);
    const a0 = this.actuatorStartOf(s);
    seg.actuatorStart = a0;
    seg.actuatorRate = a0.length > 0 ? actuatorRate(a0, actuatorEnd as number[], length) : a0;
    seg.accel = plans.accelAt(offset);
    seg.cruise2 = r[o + CRUISE2];
    seg.maxEntry2 = plans.maxEntry2At(offset);
    if (plans.isFinal(offset)) {
      seg.entry2 = plans.finalEntry2(offset);
      seg.exit2 = plans.finalExit2(offset);
      seg.state = 'planned';
      seg.time();
    }
    return seg;
  }

  /** Drops slot s's references, so that the store keeps nothing alive once a segment left it. */
  private release(s: number): void {
    if (this.records[s * this.stride + HAS_REFS] === 0) return;
    this.events[s] = undefined;
    this.actuatorStarts[s] = undefined;
    this.actuatorEnds[s] = undefined;
  }

  /** Doubles the ring, moving the entries to slots 0 … count − 1. */
  private grow(): void {
    const capacity = 2 * (this.mask + 1);
    const stride = this.stride;
    const records = new Float64Array(capacity * stride);
    const orderRefs = <T>(from: (T | undefined)[]): (T | undefined)[] => {
      const to = new Array<T | undefined>(capacity);
      for (let i = 0; i < this.count; i++) to[i] = from[(this.head + i) & this.mask];
      return to;
    };
    for (let i = 0; i < this.count; i++) {
      const o = ((this.head + i) & this.mask) * stride;
      records.set(this.records.subarray(o, o + stride), i * stride);
    }
    this.records = records;
    this.events = orderRefs(this.events);
    this.actuatorStarts = orderRefs(this.actuatorStarts);
    this.actuatorEnds = orderRefs(this.actuatorEnds);
    this.head = 0;
    this.mask = capacity - 1;
  }
}
