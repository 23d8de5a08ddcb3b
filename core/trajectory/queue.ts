/**
 * The trajectory queue: the author's copy of the distributed trajectory object.
 *
 * Segments move through the paper's four states (Figure 3):
 *   unplanned   appended; its speeds may still rise as more path arrives
 *   planned     behind the planner's planned pointer: its profile is final and timed
 *   transmitted locked: sent to the readers, never edited again
 *   historical  executed (its end time has passed)
 *
 * Untransmitted moves can be cancelled or replaced; the plan is redone from there.
 * The queue is bounded: it holds `capacity` untransmitted segments, and more only
 * while the lookahead needs more path to be final (hasRoom: as deep as braking
 * needs, however short the segments); producers wait for room (reserveSlot), so a
 * loop of addSegmentToQueue calls paces itself to the machine. An executor (the device sessions, or a dry run) takes
 * segments from the front with transmitNext() and retires them with retireUntil()
 * as time passes.
 *
 * Untransmitted single-segment lines appended while nobody listens are kept as
 * columns (pendingSegments.ts), not objects, until a segment is transmitted or the
 * untransmitted path is read or edited as objects (materialize): a deep lookahead
 * then costs no garbage-collector time. docs/architecture.md §3 has the rules.
 */
import { MaxlError } from '../errors.ts';
import type { ResolvedConfig } from '../config/types.ts';
import { LookaheadPlanner } from '../plan/lookahead.ts';
import { shouldDropSpent } from '../plan/spentPrefix.ts';
import { buildEventTracks, type EventTrack } from './events.ts';
import { actuatorPosition } from '../config/transforms.ts';
import {
  actuatorRate,
  directionInto,
  floorCruise2,
  hasNonlinearTransform,
  segmentsForMove,
  tailAfter,
  validateMove,
  ZERO_LENGTH_MM,
  type Move,
  type PathTail,
  type ValidatedMove,
} from './moves.ts';
import { PendingSegments, type PendingFront } from './pendingSegments.ts';
import { LineLimits } from './lineLimits.ts';
import { RoomGate } from './roomGate.ts';
import { TransmittedEnd } from './transmittedEnd.ts';
import type { TrajectoryHistory } from './history.ts';
import { PHASE_STRIDE, TRAPEZOID_MAX_PHASES, writeTrapezoid } from '../plan/phases.ts';
import type { QueueEventType, QueueView } from './queueView.ts';
import { Segment, type SegmentState } from './segment.ts';
import { copySegment, pointPosition, rejoinSegment, remainderOf, type PathPoint } from './restart.ts';

export type { QueueEventType };

export interface QueueEvent {
  type: QueueEventType;
  segments: readonly Segment[];
}

export type QueueListener = (event: QueueEvent) => void;

export interface MoveReceipt {
  moveId: number;
  /** The segments the move became: one, or several when a nonlinear transform subdivided it. */
  segmentIds: number[];
  /** True for a zero-length move that sets no event, which adds nothing. (One that sets events is a 0-s dwell.) */
  skipped: boolean;
}

/**
 * The most untransmitted segments the queue takes for the lookahead's sake (beyond
 * its capacity). 65 536 segments hold the 10.4 mm that braking from 250 mm/s at
 * 3 000 mm/s² needs down to 0.16 µm per segment; on a finer path the plan brakes
 * earlier than it must (slower, never unsafe). It bounds the memory a path of
 * near-zero segments could take: about 0.2 kB a segment in the columnar tail and
 * the planner's store (14 MB at the bound), about 0.6 kB as segment objects (a
 * queue someone listens to: 40 MB).
 */
export const MAX_LOOKAHEAD_SEGMENTS = 65_536;

/** The tracks of a segment that sets no event channel. */
const NO_EVENTS: EventTrack[] = [];

const LOCKED_MESSAGE = 'has already been transmitted; transmitted segments are locked';

/** The queue, with its editing and executing methods: owned by Maxl and the streamer; apps read it through QueueView. */
export class TrajectoryQueue implements QueueView {
  readonly config: ResolvedConfig;
  readonly capacity: number;
  /** Zero-length moves (setting no event) skipped so far. */
  skippedZeroLength = 0;
  /** Floor on every new segment's duration, s (the links' limit: net/linkFeedLimit.ts); 0 for none. */
  private minSegmentDuration_s = 0;

  /**
   * Live segments as objects (transmitted, then untransmitted) in path order from
   * live[head]; the last `untransmitted` of them are untransmitted. The rest of the
   * untransmitted path follows them in `pending`, as columns (pendingSegments.ts):
   * the planner's blocks are live's untransmitted ones, then pending's. Every method
   * that reads or edits the untransmitted path as objects first moves pending into
   * live (materialize); only appending a single-segment line with nobody listening,
   * planning and transmitting the front work on the columns.
   */
  private live: Segment[] = [];
  private head = 0;
  private untransmitted = 0;
  private readonly pending: PendingSegments;
  /** Whether single-segment lines may go to `pending`: no nonlinear transform subdivides moves. */
  private readonly columnar: boolean;
  /** Two unit-vector buffers for columnar appends: the tail's direction is one, the new segment's the other. */
  private readonly unitBuffers: [number[], number[]];
  /** The machine's limits as a line's planner inputs need them. */
  private readonly lineLimits: LineLimits;
  private readonly planner: LookaheadPlanner;
  /** Segments finalised during the current call, reported once it returns. */
  private newlyPlanned: Segment[] = [];
  private nextSegmentId = 1;
  private nextMoveId = 1;
  /** End of the path as appended so far (mutated in place). */
  private readonly tail: PathTail;
  /** Where the transmitted path ends: time, speed, event values and the path's tail there. */
  private readonly transmitted: TransmittedEnd;
  private listeners: QueueListener[] = [];
  /** Producers waiting for room, oldest first, and slots promised to woken ones. */
  private readonly gate = new RoomGate();

  /** The author's as-planned history: each segment is recorded as it is locked, before listeners hear of it. */
  private readonly history: TrajectoryHistory | undefined;
  /** executeFrontNow()'s reused buffers: the front's fields, and its packed timing when there is no history to write it into. */
  private readonly front: PendingFront;
  private readonly timingBuffer = new Float64Array(TRAPEZOID_MAX_PHASES * PHASE_STRIDE);

  constructor(config: ResolvedConfig, initialPosition?: number[], history?: TrajectoryHistory) {
    this.config = config;
    this.history = history;
    this.capacity = config.queueCapacity;
    const position = initialPosition ? [...initialPosition] : new Array<number>(config.motionAxes.length).fill(0);
    this.tail = { position, unit: null, cruise2: 0 };
    this.transmitted = new TransmittedEnd(config.motionAxes.length, config.eventChannels.length);
    this.planner = new LookaheadPlanner(this.capacity, (offset, entry2, exit2) => this.onPlanned(offset, entry2, exit2));
    const axes = config.motionAxes.length;
    this.pending = new PendingSegments(axes);
    this.columnar = !hasNonlinearTransform(config);
    this.unitBuffers = [new Array<number>(axes).fill(0), new Array<number>(axes).fill(0)];
    const zeros = () => new Array<number>(axes).fill(0);
    this.front = { start: zeros(), end: zeros(), unit: zeros(), events: [], actuatorStart: [], actuatorEnd: null, length: 0, accel: 0, cruise2: 0 };
    this.lineLimits = new LineLimits(config.limits);
  }

  /**
   * Sets a floor on the duration of segments added from now on (s; 0 for none): the
   * runtime's, so that the links can carry them (net/linkFeedLimit.ts). Segments
   * already queued keep their caps.
   */
  setMinSegmentDuration(seconds: number): void {
    if (!(seconds >= 0) || !Number.isFinite(seconds)) throw new MaxlError('CONFIG_INVALID', `must be a finite duration ≥ 0 s, got ${seconds}`, 'minSegmentDuration');
    this.minSegmentDuration_s = seconds;
  }

  // --- reading ---

  /** Live segments in path order (a copy). */
  segments(): Segment[] {
    this.materialize();
    return this.live.slice(this.head);
  }

  get size(): number {
    return this.live.length - this.head + this.pending.size;
  }

  get untransmittedCount(): number {
    return this.untransmitted + this.pending.size;
  }

  /**
   * Whether a producer may append now: while fewer than `capacity` segments are
   * untransmitted, and beyond that for as long as the lookahead needs more path
   * (none of them is final yet: the path known after the first is shorter than
   * braking from the speed it may reach there; plan/lookahead.ts). So the depth of
   * the lookahead is a braking distance, however short the segments, and an
   * executor that waits for room locks only final segments: the plan is the one
   * planPath makes of the whole path. Past `capacity` one producer at a time is let
   * in (no slot promised yet), as each appended move may make the front final.
   * MAX_LOOKAHEAD_SEGMENTS bounds the memory on absurdly fine paths.
   */
  hasRoom(): boolean {
    const untransmitted = this.untransmitted + this.pending.size;
    const reserved = this.gate.reserved;
    if (untransmitted + reserved < this.capacity) return true;
    return reserved === 0 && this.planner.needsMorePath && untransmitted < MAX_LOOKAHEAD_SEGMENTS;
  }

  /** The end of the path as appended so far (mm, motion axes). */
  get tailPosition(): readonly number[] {
    return this.tail.position;
  }

  /** Author µs at which the transmitted path ends. −∞ before anything is transmitted. */
  get transmittedEnd_us(): number {
    return this.transmitted.end_us;
  }

  /** Whether the machine will still be moving at the end of the transmitted path. */
  get transmittedEndsMoving(): boolean {
    return this.transmitted.exit2 > 0;
  }

  /** A live segment by id (ids are unique, but pieces of a split segment are numbered after it). */
  get(id: number): Segment | undefined {
    this.materialize();
    for (let i = this.live.length - 1; i >= this.head; i--) if (this.live[i].id === id) return this.live[i];
    return undefined;
  }

  /** The i-th untransmitted segment (0 = the next to transmit), if any. */
  untransmittedAt(i: number): Segment | undefined {
    this.materialize();
    return i >= 0 && i < this.untransmitted ? this.live[this.live.length - this.untransmitted + i] : undefined;
  }

  /** The first segment not yet transmitted, if any. */
  peekUntransmitted(): Segment | undefined {
    this.materialize();
    return this.untransmitted > 0 ? this.live[this.live.length - this.untransmitted] : undefined;
  }

  /**
   * Fills in the provisional speeds of unplanned segments (as if the path ended
   * at rest now), for display. Final plans are untouched.
   */
  provisionalPlan(): void {
    this.materialize();
    const first = this.live.length - this.untransmitted;
    this.planner.fillProvisional((offset, entry2, exit2) => {
      const seg = this.live[first + offset];
      seg.entry2 = entry2;
      seg.exit2 = exit2;
    });
  }

  /**
   * A segment's event tracks, sampled from its evaluators. Built once its timing is
   * final; throws the evaluator's MaxlError if one failed.
   */
  eventTracksOf(seg: Segment): EventTrack[] {
    if (seg.eventTracks === null) {
      const timing = seg.timing;
      if (timing === null) throw new MaxlError('SEGMENT_NOT_FOUND', `segment ${seg.id} is not timed yet`);
      seg.eventTracks =
        seg.events.length === 0
          ? NO_EVENTS
          : buildEventTracks(seg.events, { ...geometryOf(seg), timing }, this.config.motionAxes, this.config.actuatorAxes, this.config.eventChannels);
    }
    return seg.eventTracks;
  }

  subscribe(listener: QueueListener): () => void {
    // A listener hears of segments as objects: the columnar tail becomes objects now, and stays so while anyone listens.
    this.materialize();
    this.listeners = [...this.listeners, listener];
    return () => {
      this.listeners = this.listeners.filter((l) => l !== listener);
    };
  }

  // --- producing ---

  /** Validates a move against the end of the path as it stands. Throws on bad input, changes nothing. */
  validate(move: Move, from: readonly number[] = this.tail.position): ValidatedMove {
    return validateMove(this.config, move, from);
  }

  /**
   * Resolves when a slot is reserved for the caller, who must then call
   * appendValidated(move, true). Waiters are served in the order they came.
   */
  reserveSlot(signal?: AbortSignal): Promise<void> {
    return this.gate.reserve(!signal?.aborted && this.hasRoom(), signal);
  }

  /** Gives back a slot from reserveSlot() that will not be used (its move was abandoned). */
  releaseSlot(): void {
    this.gate.release();
    this.wakeWaiters();
  }

  /**
   * Appends a validated move now. `reserved` says the caller holds a slot from
   * reserveSlot(); without one the move is appended whether or not there is room.
   */
  appendValidated(move: ValidatedMove, reserved = false): MoveReceipt {
    if (reserved) this.gate.release();
    // The move's id is taken only once its segments exist (a transform may refuse them).
    const receipt = this.enqueue(move, this.nextMoveId, null);
    this.nextMoveId++;
    this.flushPlanned();
    // Past capacity the lookahead lets one producer in at a time: the next may come in if
    // this move left the front still short of the path it needs.
    if (this.gate.waiting > 0) this.wakeWaiters();
    return receipt;
  }

  /** Validates and appends in one step, ignoring the capacity bound. */
  append(move: Move): MoveReceipt {
    return this.appendValidated(this.validate(move));
  }

  /** Turns a move into segments at the tail and plans them; `added` collects them for an edit's report. */
  private enqueue(move: ValidatedMove, moveId: number, added: Segment[] | null): MoveReceipt {
    if (added === null && this.columnar && move.dwell_s === null && this.listeners.length === 0) {
      const receipt = this.enqueueLine(move, moveId);
      if (receipt !== null) return receipt;
    }
    this.materialize();
    const segments = segmentsForMove(this.config, move, this.tail, this.nextSegmentId, moveId, this.minSegmentDuration_s);
    if (segments.length === 0) {
      this.skippedZeroLength++;
      return { moveId, segmentIds: [], skipped: true };
    }
    this.nextSegmentId += segments.length;
    for (const seg of segments) {
      this.live.push(seg);
      this.untransmitted++;
      this.planner.appendBlock(seg);
    }
    const last = segments[segments.length - 1];
    tailAfter(last, this.tail);
    if (added) for (const seg of segments) added.push(seg);
    else this.emit('added', segments);
    return { moveId, segmentIds: segments.length === 1 ? [segments[0].id] : segments.map((s) => s.id), skipped: false };
  }

  /**
   * Appends a linear move as one segment in the columnar tail: segmentsForMove's
   * one-piece case (moves.ts), without making the object. A zero-length move that
   * sets no event is skipped here too; one that sets events (a 0-s dwell) returns
   * null, with nothing changed, for the object path.
   */
  private enqueueLine(move: ValidatedMove, moveId: number): MoveReceipt | null {
    const tail = this.tail;
    const unit = tail.unit === this.unitBuffers[0] ? this.unitBuffers[1] : this.unitBuffers[0];
    const length = directionInto(tail.position, move.end, unit);
    if (length < ZERO_LENGTH_MM) {
      if (move.events.length > 0) return null;
      this.skippedZeroLength++;
      return { moveId, segmentIds: [], skipped: true };
    }
    const limits = this.lineLimits;
    const cruise2 = floorCruise2(limits.cruise2(move.maxVelocity, unit), length, this.minSegmentDuration_s);
    const accel = limits.accel(move.maxAcceleration, unit);
    const maxEntry2 = limits.entryCap2(tail.unit, tail.cruise2, unit, cruise2);
    const id = this.nextSegmentId++;
    this.pending.push(id, moveId, move, tail.position, unit, cruise2, actuatorPosition(this.config.transforms, tail.position));
    this.planner.append(length, accel, maxEntry2);
    tail.position = move.end;
    tail.unit = unit;
    tail.cruise2 = cruise2;
    return { moveId, segmentIds: [id], skipped: false };
  }

  /** Moves the columnar tail into `live` as objects, so that the untransmitted path is all objects. */
  private materialize(): void {
    if (this.pending.size === 0) return;
    const segments = this.pending.takeAll(this.planner, this.untransmitted);
    for (let i = 0; i < segments.length; i++) this.live.push(segments[i]);
    this.untransmitted += segments.length;
  }

  // --- editing ---

  /** Cancels an untransmitted move (all its segments). Later moves now start where the one before it ended. */
  cancel(moveId: number): void {
    this.materialize();
    this.edit(this.untransmittedIndexOf(moveId), null, true);
  }

  /** Replaces an untransmitted move by another. Later moves keep their end positions. */
  replace(moveId: number, move: Move): MoveReceipt {
    this.materialize();
    const index = this.untransmittedIndexOf(moveId);
    return this.edit(index, this.validate(move, this.live[index].start), true) as MoveReceipt;
  }

  /** Cancels an untransmitted move (all its segments) and every move after it. */
  cancelMovesFrom(moveId: number): void {
    this.materialize();
    this.edit(this.untransmittedIndexOf(moveId), null, false);
  }

  /** Cancels every untransmitted segment. */
  cancelAll(): void {
    this.materialize();
    if (this.untransmitted > 0) this.edit(this.live.length - this.untransmitted, null, false);
  }

  /** Cancels the untransmitted segment `id` and everything after it. */
  cancelFrom(id: number): void {
    this.materialize();
    const first = this.live.length - this.untransmitted;
    const index = this.live.findIndex((seg, i) => i >= first && seg.id === id);
    if (index < 0) {
      if (this.get(id)) throw new MaxlError('SEGMENT_LOCKED', `segment ${id} ${LOCKED_MESSAGE}`);
      throw new MaxlError('SEGMENT_NOT_FOUND', `there is no segment ${id}`);
    }
    this.edit(index, null, false);
  }

  /**
   * Splits the first untransmitted segment `distance` mm along it into two
   * segments of the same move, so that an executor can lock only the first piece:
   * only as much of the path as it must, however long the segments. A straight
   * junction within a move does not limit speed, so the plan is the same as before
   * the split. Returns the two pieces.
   */
  splitFront(distance: number): [Segment, Segment] {
    this.materialize();
    const index = this.live.length - this.untransmitted;
    const seg = this.live[index];
    if (!seg) throw new MaxlError('SEGMENT_NOT_FOUND', 'there is no untransmitted segment to split');
    if (!(distance > ZERO_LENGTH_MM && distance < seg.length - ZERO_LENGTH_MM)) {
      throw new MaxlError('MOVE_INVALID', `cannot split a ${seg.length} mm segment at ${distance} mm`, 'distance');
    }
    return this.splitAt(index, distance, false);
  }

  /**
   * Plans the machine to rest as soon as its limits allow, along the path: from
   * the speed the transmitted path leaves it at, braking at each segment's
   * acceleration limit through the untransmitted segments. The segment in which
   * it comes to rest is split there, and the path after that point starts from
   * rest. Returns the first segment after the stopping point (for an executor to
   * hold back, or to cancel from), or null if the path ends first.
   */
  brakeToRest(): Segment | null {
    this.materialize();
    let v2 = this.planner.frontSpeed2;
    const first = this.live.length - this.untransmitted;
    for (let i = first; i < this.live.length; i++) {
      const seg = this.live[i];
      // The plan comes to rest before every dwell, and braking at the same limits from
      // a speed no higher does too: hold before the dwell, its events not yet set.
      if (seg.isDwell) return this.restBefore(i);
      const reach = 2 * seg.accel * seg.length;
      if (v2 >= reach && i + 1 < this.live.length) {
        v2 -= reach;
        continue;
      }
      if (v2 >= reach) return null; // rest only at the end of the path, which plans to rest anyway
      // At rest after d = v²/2a into this segment.
      const d = v2 / (2 * seg.accel);
      if (d <= ZERO_LENGTH_MM) return this.restBefore(i);
      if (d >= seg.length - ZERO_LENGTH_MM) return i + 1 < this.live.length ? this.restBefore(i + 1) : null;
      return this.splitAt(i, d, true)[1];
    }
    return null;
  }

  /** Makes live[index] start from rest (its entry cap 0), replanning from there. */
  private restBefore(index: number): Segment {
    const seg = this.live[index];
    this.replanFrom(index, () => {
      seg.maxEntry2 = 0;
    });
    return seg;
  }

  /** Splits live[index] at `distance`; with `rest`, the second piece starts from rest. */
  private splitAt(index: number, distance: number, rest: boolean): [Segment, Segment] {
    const seg = this.live[index];
    const mid = seg.start.map((p, i) => p + seg.unit[i] * distance);
    const make = (id: number, start: number[], end: number[], length: number, offset: number, actuatorStart: number[]) => {
      const piece = new Segment(id, seg.moveId, start, end, seg.unit, length, offset, seg.source);
      piece.actuatorStart = actuatorStart;
      piece.actuatorRate = seg.actuatorRate;
      piece.accel = seg.accel;
      // The piece keeps the whole segment's cap, floor or none: a slice may be far shorter than
      // the floor allows at the speed the machine already runs into it, and splitting costs the
      // link one segment more, not a stream of them.
      piece.cruise2 = seg.cruise2;
      return piece;
    };
    const a = make(this.nextSegmentId++, seg.start, mid, distance, seg.moveOffset, seg.actuatorStart);
    const b = make(
      this.nextSegmentId++,
      mid,
      seg.end,
      seg.length - distance,
      seg.moveOffset + distance,
      seg.actuatorStart.map((p, j) => p + seg.actuatorRate[j] * distance),
    );
    a.maxEntry2 = seg.maxEntry2;
    b.maxEntry2 = rest ? 0 : seg.cruise2; // straight on: only the cruise cap applies
    this.replanFrom(index, () => {
      this.live.splice(index, 1, a, b);
      this.untransmitted++;
    });
    this.emit('removed', [seg]);
    this.emit('added', [a, b]);
    this.flushPlanned();
    return [a, b];
  }

  /**
   * Re-runs the planner over the untransmitted segments from live[index] on, after
   * `change` has edited them in place. Ids change for neither the kept segments nor
   * their order; planned states are recomputed.
   */
  private replanFrom(index: number, change: () => void): void {
    const wasPlanned = this.reopenPlanFrom(index, false);
    change();
    for (let i = index; i < this.live.length; i++) this.planner.appendBlock(this.live[i]);
    this.settleReplan(wasPlanned);
  }

  /** Index in `live` of a move's first segment, which must be untransmitted, as must the whole move. */
  private untransmittedIndexOf(moveId: number): number {
    const first = this.live.length - this.untransmitted;
    for (let i = first; i < this.live.length; i++) {
      if (this.live[i].moveId !== moveId) continue;
      if (i > this.head && this.live[i - 1].moveId === moveId) {
        throw new MaxlError('SEGMENT_LOCKED', `part of move ${moveId} ${LOCKED_MESSAGE}`);
      }
      return i;
    }
    if (moveId > 0 && moveId < this.nextMoveId) throw new MaxlError('SEGMENT_LOCKED', `move ${moveId} ${LOCKED_MESSAGE}`);
    throw new MaxlError('SEGMENT_NOT_FOUND', `there is no move ${moveId}`);
  }

  /**
   * Removes the untransmitted segments from live[index] on, then appends
   * `replacement` (if any) and, when `keepLater`, the moves after the first one
   * removed, each from the new end of the path. Refused, with nothing changed, if
   * the moving machine could no longer brake in time.
   */
  private edit(index: number, replacement: ValidatedMove | null, keepLater: boolean): MoveReceipt | undefined {
    const firstUntransmitted = this.live.length - this.untransmitted;
    const planIndex = index - firstUntransmitted;
    const removed = this.live.slice(index);
    const editedMove = removed[0].moveId;
    const later: Segment[] = []; // one segment per later move, carrying its source move
    if (keepLater) for (const seg of removed) if (seg.moveId !== editedMove && seg.moveId !== later[later.length - 1]?.moveId) later.push(seg);
    const oldTail = { ...this.tail };
    const wasPlanned = this.reopenPlanFrom(index, true);
    // The tail before the first segment removed: the untransmitted one before it, else the transmitted path's end.
    if (index > this.live.length - this.untransmitted) tailAfter(this.live[index - 1], this.tail);
    else if (!this.transmitted.restoreTail(this.tail)) Object.assign(this.tail, { position: removed[0].start, unit: null, cruise2: 0 });

    const added: Segment[] = [];
    const receipt = replacement ? this.enqueue(replacement, this.nextMoveId++, added) : undefined;
    for (const seg of later) this.enqueue(seg.source, seg.moveId, added);

    if (!this.planner.isFeasible()) {
      // Undo: the machine is already committed to a speed this path cannot absorb.
      this.truncateTo(index, planIndex);
      for (const seg of removed) {
        this.live.push(seg);
        this.untransmitted++;
        this.planner.appendBlock(seg);
      }
      Object.assign(this.tail, oldTail);
      this.settleReplan(wasPlanned);
      throw new MaxlError(
        'CANNOT_STOP_IN_PATH',
        'the machine is already committed to a speed that this change would not leave room to brake from; stop the machine first, or edit moves further ahead',
      );
    }
    this.settleReplan(wasPlanned);
    this.emit('removed', removed);
    this.emit('added', added);
    this.flushPlanned();
    this.wakeWaiters();
    return receipt;
  }

  /**
   * Opens a replan from live[index], the first step of every edit: every
   * untransmitted segment becomes unplanned (onPlanned marks the final ones again),
   * and the planner drops its blocks from live[index] on; with `cut`, so does live.
   * Returns the segments that were planned, for settleReplan once the edit is done.
   */
  private reopenPlanFrom(index: number, cut: boolean): Segment[] {
    const firstUntransmitted = this.live.length - this.untransmitted;
    const wasPlanned = this.live.slice(firstUntransmitted).filter((seg) => seg.state === 'planned');
    for (let i = firstUntransmitted; i < this.live.length; i++) this.live[i].state = 'unplanned';
    this.newlyPlanned = [];
    if (cut) this.truncateTo(index, index - firstUntransmitted);
    else this.planner.truncate(index - firstUntransmitted);
    return wasPlanned;
  }

  private truncateTo(index: number, planIndex: number): void {
    const dropped = this.planner.truncate(planIndex);
    this.live.length = index;
    this.untransmitted -= dropped;
  }

  /**
   * After an edit replanned the untransmitted segments: those that were planned
   * and no longer are lose their timing and are reported as 'replanned'; only
   * segments that became planned are reported as 'planned'.
   */
  private settleReplan(wasPlanned: Segment[]): void {
    const before = new Set(wasPlanned);
    const live = new Set(this.live.slice(this.live.length - this.untransmitted));
    const dropped = wasPlanned.filter((seg) => seg.state === 'unplanned' && live.has(seg));
    for (const seg of dropped) seg.untime();
    this.newlyPlanned = this.newlyPlanned.filter((seg) => !before.has(seg));
    this.emit('replanned', dropped);
  }

  // --- executing ---

  /**
   * Locks the first untransmitted segment and gives it its start time in author µs:
   * right after the transmitted path if the machine is still moving there, else at
   * `earliestStart_us` or later. Returns undefined when nothing is queued.
   * Throws the MaxlError of a failed event evaluator, leaving the segment queued.
   */
  transmitNext(earliestStart_us: number): Segment | undefined {
    const next = this.timeFront();
    if (next === undefined) return undefined;
    const tracks = this.eventTracksOf(next);
    const seg = next;
    // One fewer untransmitted first: blocks that lockFront() finalises are reported by offset from the new front.
    this.untransmitted--;
    seg.exit2 = this.planner.lockFront();
    const end = this.transmitted;
    seg.startTime_us = end.nextStart_us(earliestStart_us);
    seg.state = 'transmitted';
    seg.eventsAtStart = end.eventValues;
    if (tracks.length > 0) {
      const values = [...end.eventValues];
      for (const t of tracks) values[t.channel] = t.values[t.values.length - 1];
      end.eventValues = values;
    }
    end.lock(seg.endTime_us, seg.exit2, seg.end, seg.isDwell ? null : seg.unit, seg.isDwell ? 0 : seg.cruise2);
    this.history?.push(seg);
    if (this.listeners.length > 0) this.emit('transmitted', [seg]);
    this.flushPlanned();
    this.wakeWaiters();
    return seg;
  }

  /**
   * Locks the first untransmitted segment as transmitNext() does, and has it run at
   * once: everything transmitted before it retires as it starts, and it is recorded
   * in the history as executed (a dry run's executor: dryRun.ts). A columnar
   * segment (pendingSegments.ts) that sets no event, with nobody listening, is
   * timed and recorded from its columns and never made into an object; any other
   * goes through transmitNext() and stays live, transmitted, until the next.
   * Returns its duration (s), or −1 when nothing is queued.
   */
  executeFrontNow(earliestStart_us: number): number {
    if (this.untransmitted > 0 || this.pending.size === 0 || this.listeners.length > 0) return this.executeObjectFront(earliestStart_us);
    const f = this.pending.readFront(this.front, this.planner);
    if (f.events.length > 0) return this.executeObjectFront(earliestStart_us);
    const end = this.transmitted;
    const start_us = end.nextStart_us(earliestStart_us);
    // Whatever was transmitted ends by start_us (the transmitted path's end, or earlier).
    if (this.head < this.live.length) this.retireUntil(start_us);
    // As timeFront() and transmitNext(): the front speed (a final plan's entry is the front speed too); the exit is lockFront()'s.
    const entry2 = this.planner.frontSpeed2;
    this.pending.dropFront();
    const exit2 = this.planner.lockFront();
    // Segment.time()'s trapezoid and duration, written into the history's ring (or a buffer) instead of a new array.
    let duration_s: number;
    if (this.history) {
      const a0 = f.actuatorStart;
      const rate = a0.length > 0 ? actuatorRate(a0, f.actuatorEnd as number[], f.length) : a0;
      duration_s = this.history.pushTrapezoid(start_us, f.length, entry2, exit2, f.cruise2, f.accel, f.start, f.unit, a0, rate, end.eventValues);
    } else {
      const last = (writeTrapezoid(this.timingBuffer, 0, f.length, entry2, exit2, f.cruise2, f.accel) - 1) * PHASE_STRIDE;
      duration_s = this.timingBuffer[last] + this.timingBuffer[last + 1];
    }
    end.lock(start_us + duration_s * 1e6, exit2, f.end, f.unit, f.cruise2);
    // Nothing before it is held any more (all ran), so live holds no segment out of path order.
    if (this.head === this.live.length && this.head > 0) {
      this.live.length = 0;
      this.head = 0;
    }
    this.flushPlanned();
    this.wakeWaiters();
    return duration_s;
  }

  /** executeFrontNow() for a segment that must be an object: transmitted, then retired with all before it. */
  private executeObjectFront(earliestStart_us: number): number {
    const seg = this.transmitNext(earliestStart_us);
    if (seg === undefined) return -1;
    this.retireUntil(seg.endTime_us);
    return seg.duration_s;
  }

  /**
   * The first untransmitted segment, timed as transmitNext() would lock it now
   * (its exit speed as the plan stands, if that is not final yet).
   */
  timeFront(): Segment | undefined {
    if (this.untransmitted === 0) {
      if (this.pending.size === 0) return undefined;
      // The front is columnar: its object is made now, as it is about to be sent.
      this.live.push(this.pending.takeFront(this.planner, 0));
      this.untransmitted = 1;
    }
    const next = this.live[this.live.length - this.untransmitted];
    if (next.state !== 'planned') {
      next.entry2 = this.planner.frontSpeed2;
      next.exit2 = this.planner.frontExit2();
      next.time();
    }
    return next;
  }

  /** Author µs at which the next transmitted segment would start, given the earliest start allowed. */
  nextStart_us(earliestStart_us: number): number {
    return this.transmitted.nextStart_us(earliestStart_us);
  }

  /** Squared speed (mm²/s²) at which the transmitted path ends. */
  get transmittedExit2(): number {
    return this.transmitted.exit2;
  }

  /**
   * Finalises the plan of every queued segment as if nothing more will come
   * (the end of a job). Without it the last segments stay unplanned until locked.
   */
  planToRest(): void {
    this.planner.planToRest();
    this.flushPlanned();
  }

  /** Moves transmitted segments that ended at or before `now_us` to historical, and returns them. */
  retireUntil(now_us: number): Segment[] {
    const first = this.head;
    while (this.head < this.live.length) {
      const seg = this.live[this.head];
      if (seg.state !== 'transmitted' || seg.endTime_us > now_us) break;
      seg.state = 'historical';
      this.head++;
    }
    const retired = new Array<Segment>(this.head - first);
    for (let i = 0; i < retired.length; i++) retired[i] = this.live[first + i];
    if (shouldDropSpent(this.head, this.live.length)) {
      this.live = this.live.slice(this.head);
      this.head = 0;
    }
    this.emit('historical', retired);
    return retired;
  }

  /**
   * Rebuilds the path for a job resumed after the machine stopped off its plan (a
   * link lost, a device rebooted, a HALT, a refused segment: core/runtime.ts):
   *   - `stop`: where the path resumes (the point the readers stopped at, the one
   *     furthest back when they stopped apart);
   *   - `rerun`: the segments transmitted after stop.segment that never ran, in path
   *     order; they are run again as untimed copies;
   *   - `rejoinFrom`: when boards stopped apart, the furthest point one reached: a
   *     straight segment from there to `stop` comes first, on which they meet.
   * The rest of stop.segment follows, then the copies, then every untransmitted
   * segment after it, unchanged: nothing is lost and nothing runs twice. The whole
   * path is replanned from rest; transmitted segments left behind become historical.
   * Returns the untransmitted segments, in order.
   */
  restartFrom(stop: PathPoint, rerun: readonly Segment[], rejoinFrom: number[] | null): Segment[] {
    this.materialize();
    const first = this.live.length - this.untransmitted;
    const stopIndex = this.live.indexOf(stop.segment);
    const kept = stopIndex >= first ? this.live.slice(stopIndex + 1) : this.live.slice(first);
    const keptSet = new Set(kept);
    const dropped = this.live.slice(first).filter((seg) => !keptSet.has(seg));
    // Event values where the path resumes: as the stopped segment began (its own
    // changes are sent again with its remainder), else at the transmitted path's end.
    const events = stop.segment.eventsAtStart ? [...stop.segment.eventsAtStart] : [...this.transmitted.eventValues];

    const fresh: Segment[] = [];
    if (rejoinFrom) fresh.push(rejoinSegment(this.config, rejoinFrom, stop, this.nextSegmentId++));
    const rest = remainderOf(stop, this.nextSegmentId);
    if (rest) {
      this.nextSegmentId++;
      fresh.push(rest);
    }
    for (const seg of rerun) fresh.push(copySegment(seg, this.nextSegmentId++));

    for (let i = this.head; i < first; i++) this.live[i].state = 'historical';
    for (const seg of kept) {
      seg.state = 'unplanned';
      seg.untime();
    }
    this.newlyPlanned = [];
    this.planner.clearToRest();
    this.live = [...fresh, ...kept];
    this.head = 0;
    this.untransmitted = this.live.length;
    for (const seg of this.live) this.planner.appendBlock(seg);
    this.transmitted.restart(events);
    if (this.live.length === 0) Object.assign(this.tail, { position: pointPosition(stop), unit: null, cruise2: 0 });
    this.emit('removed', dropped);
    this.emit('replanned', kept);
    this.emit('added', fresh);
    this.flushPlanned();
    this.wakeWaiters();
    return this.live.slice();
  }

  // --- internals ---

  /** The planner's report of a final plan, by offset from the first untransmitted segment. */
  private onPlanned(offset: number, entry2: number, exit2: number): void {
    // In the columnar tail: the object, when made, is planned and timed from the planner's final plan.
    if (offset >= this.untransmitted) return;
    const seg = this.live[this.live.length - this.untransmitted + offset];
    seg.entry2 = entry2;
    seg.exit2 = exit2;
    seg.time();
    if (seg.state === 'unplanned') {
      seg.state = 'planned';
      this.newlyPlanned.push(seg);
    }
  }

  private flushPlanned(): void {
    const planned = this.newlyPlanned;
    if (planned.length === 0) return;
    if (this.listeners.length === 0) {
      // Nobody will hold it: empty it for the next call (pop is cheaper than setting length).
      while (planned.length > 0) planned.pop();
      return;
    }
    this.newlyPlanned = [];
    // A segment planned during this call may already have been transmitted by it.
    let still = planned;
    for (const s of planned) {
      if (s.state !== 'planned') {
        still = planned.filter((p) => p.state === 'planned');
        break;
      }
    }
    this.emit('planned', still);
  }

  private emit(type: QueueEventType, segments: readonly Segment[]): void {
    if (segments.length === 0) return;
    const listeners = this.listeners;
    for (let i = 0; i < listeners.length; i++) listeners[i]({ type, segments });
  }

  private wakeWaiters(): void {
    while (this.gate.waiting > 0 && this.hasRoom()) this.gate.admitNext();
  }
}

function geometryOf(seg: Segment) {
  return {
    length: seg.length,
    moveOffset: seg.moveOffset,
    start: seg.start,
    unit: seg.unit,
    actuatorStart: seg.actuatorStart,
    actuatorRate: seg.actuatorRate,
  };
}

export type { SegmentState };
