/**
 * The trajectory queue's store: the segments it holds, appending to them, and the
 * hand-off to the lookahead planner. queue.ts has the whole queue and its roles;
 * this is the layer every role stands on:
 *   - the segments: live objects (transmitted, then untransmitted) and the columnar
 *     tail (pendingSegments.ts), the path's tail, where the transmitted path ends;
 *   - appending (producers): validate, wait for room (hasRoom, reserveSlot), append
 *     a move as segments or as one columnar line, and hand it to the planner;
 *   - the planner's report of final plans (onPlanned), told to listeners once the
 *     call that caused them returns (flushPlanned), and waking producers that wait.
 * queueReading.ts reads the segments, tailEditing.ts edits the untransmitted tail,
 * queue.ts locks, splits and retires them for the executor.
 */
import { errorAt, MaxlError } from '../errors.ts';
import type { ResolvedConfig } from '../config/types.ts';
import { LookaheadPlanner } from '../plan/lookahead.ts';
import { actuatorPosition, NO_ACTUATORS } from '../config/transforms.ts';
import { NO_SPECS, type ResolvedEventSpec } from './events.ts';
import {
  isPlainLine,
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
import { PendingSegments } from './pendingSegments.ts';
import { LineLimits } from './lineLimits.ts';
import { RoomGate } from './roomGate.ts';
import { TransmittedEnd } from './transmittedEnd.ts';
import type { TrajectoryHistory } from './history.ts';
import type { QueueEventType } from './queueView.ts';
import type { Segment } from './segment.ts';

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

/**
 * Past the capacity, the fraction of it that may be final segments before the queue
 * has no room (hasRoom): the run an executor that waits for room takes at once.
 */
const RUN_FRACTION = 1 / 8;

/** enqueueLine's answer for a zero-length move that sets no event: skipped, nothing queued. */
const LINE_SKIPPED = 0;
/** enqueueLine's answer for a zero-length move that sets events: nothing changed; the object path makes its 0-s dwell. */
const LINE_NEEDS_OBJECT = -1;

/** The queue's segments, appending and the planner's hand-off; TrajectoryQueue (queue.ts) is the whole queue. */
export abstract class QueueCore {
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
  protected live: Segment[] = [];
  protected head = 0;
  protected untransmitted = 0;
  protected readonly pending: PendingSegments;
  /** Whether single-segment lines may go to `pending`: no nonlinear transform subdivides moves. */
  private readonly columnar: boolean;
  /** Two unit-vector buffers for columnar appends: the tail's direction is one, the new segment's the other. */
  private readonly unitBuffers: [number[], number[]];
  /** The machine's limits as a line's planner inputs need them. */
  private readonly lineLimits: LineLimits;
  protected readonly planner: LookaheadPlanner;
  /** Segments finalised during the current call, reported once it returns. */
  protected newlyPlanned: Segment[] = [];
  protected nextSegmentId = 1;
  protected nextMoveId = 1;
  /** End of the path as appended so far (mutated in place). */
  protected readonly tail: PathTail;
  /** Where the transmitted path ends: time, speed, event values and the path's tail there. */
  protected readonly transmitted: TransmittedEnd;
  protected listeners: QueueListener[] = [];
  /** Producers waiting for room, oldest first, and slots promised to woken ones. */
  private readonly gate = new RoomGate();

  /** The author's as-planned history: each segment is recorded as it is locked, before listeners hear of it. */
  protected readonly history: TrajectoryHistory | undefined;

  constructor(config: ResolvedConfig, initialPosition?: number[], history?: TrajectoryHistory) {
    this.config = config;
    this.history = history;
    this.capacity = config.queueCapacity;
    const position = initialPosition ? [...initialPosition] : new Array<number>(config.motionAxes.length).fill(0);
    this.tail = { position, unit: null, cruise2: 0 };
    this.transmitted = new TransmittedEnd(config.motionAxes.length, config.eventChannels.length);
    this.planner = new LookaheadPlanner(this.capacity, (offset) => this.onPlanned(offset));
    const axes = config.motionAxes.length;
    this.pending = new PendingSegments(axes);
    this.columnar = !hasNonlinearTransform(config);
    this.unitBuffers = [new Array<number>(axes).fill(0), new Array<number>(axes).fill(0)];
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

  /**
   * Whether a producer may append now: while fewer than `capacity` segments are
   * untransmitted, and beyond that while fewer than capacity / 8 of them are final
   * (RUN_FRACTION). Past the capacity the lookahead needs more path while none is
   * final (the path known after the first is shorter than braking from the speed
   * it may reach there; plan/lookahead.ts), so the depth of the lookahead is a
   * braking distance, however short the segments, and an executor that waits for
   * room locks only final segments: the plan is the one planPath makes of the whole
   * path. On such a fine path each append finalises about one segment; were room
   * to end at the first final one, a producer and an executor that waits for room
   * would hand over one segment at a time, alternating per point (1.2–1.3× the
   * time per point of the planner bench's fine circle, bench/planner.ts). So the
   * queue takes capacity / 8 final segments more, which the executor then takes as
   * a run. The plan is the same: more path known never changes a final plan, and
   * the executor still locks only final segments. Past `capacity` one producer at
   * a time is let in (no slot promised yet), as each appended move may make the
   * front final. At a capacity below 8 this is room while none is final.
   * MAX_LOOKAHEAD_SEGMENTS bounds the memory on absurdly fine paths.
   */
  hasRoom(): boolean {
    const untransmitted = this.untransmitted + this.pending.size;
    const reserved = this.gate.reserved;
    if (untransmitted + reserved < this.capacity) return true;
    return reserved === 0 && this.planner.plannedSize < this.capacity * RUN_FRACTION && untransmitted < MAX_LOOKAHEAD_SEGMENTS;
  }

  // --- appending ---

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

  /**
   * Appends `move` now, as appendValidated(validate(move)) would (the same segment,
   * ids, plan and receipt), if it is a plain line (moves.ts isPlainLine) that the
   * columnar tail takes; returns null, changing nothing, for any other move, which
   * the caller validates and appends. A single add's fast path (Maxl.addSegmentToQueue):
   * no ValidatedMove is made, only the copy of the end that validateMove would make.
   */
  appendIfPlainLine(move: Move): MoveReceipt | null {
    if (!this.columnar || this.listeners.length > 0 || !isPlainLine(this.config, move)) return null;
    const moveId = this.nextMoveId;
    const id = this.enqueueLine(move.endPosition.slice(), move.maxVelocity ?? Infinity, move.maxAcceleration ?? Infinity, NO_SPECS, NO_ACTUATORS, moveId);
    this.nextMoveId++;
    this.flushPlanned();
    if (this.gate.waiting > 0) this.wakeWaiters();
    return id === LINE_SKIPPED ? { moveId, segmentIds: [], skipped: true } : { moveId, segmentIds: [id], skipped: false };
  }

  /** Validates and appends in one step, ignoring the capacity bound. */
  append(move: Move): MoveReceipt {
    return this.appendValidated(this.validate(move));
  }

  /**
   * The batch producer's step: appends moves[from], moves[from + 1], … for as long as
   * the queue has room (hasRoom, checked before each), and returns
   * the index of the first move not appended (moves.length when all were). Each move
   * is validated from the path's tail and appended exactly as append() would (the
   * same segments, ids and plan as a loop of single appends), without a receipt per
   * move. A bad move throws a MaxlError naming it (`moves[i]…`) with the
   * moves before it appended and nothing of it. Producers waiting for room
   * (reserveSlot) must be served first: with any waiting it appends nothing.
   */
  appendWhileRoom(moves: readonly Move[], from: number): number {
    let i = from;
    if (this.gate.waiting > 0) return i;
    // Plain lines (moves.ts isPlainLine) skip validateMove's object: the end array is
    // the caller's, borrowed as the tail position while this call runs (the caller
    // cannot change it meanwhile) and copied once at the end, as validateMove would
    // have copied each. Everything else takes the single-move path.
    let borrowed = false;
    try {
      for (; i < moves.length && this.hasRoom(); i++) {
        const move = moves[i];
        if (this.columnar && this.listeners.length === 0 && isPlainLine(this.config, move)) {
          const id = this.enqueueLine(move.endPosition, move.maxVelocity ?? Infinity, move.maxAcceleration ?? Infinity, NO_SPECS, NO_ACTUATORS, this.nextMoveId);
          this.nextMoveId++;
          if (id !== LINE_SKIPPED) borrowed = true;
          continue;
        }
        if (borrowed) this.ownTailPosition();
        borrowed = false;
        this.appendValidated(this.validateAt(moves, i));
      }
    } finally {
      if (borrowed) this.ownTailPosition();
      // Final plans of object segments (those before the columnar tail) that nobody was told of yet.
      this.flushPlanned();
    }
    return i;
  }

  /** Makes the tail position an array of the queue's own (a copy of one borrowed from a caller). */
  private ownTailPosition(): void {
    this.tail.position = this.tail.position.slice();
  }

  /** Validates moves[i] from the path's tail; a bad one throws with its index in the field (`moves[i].endPosition`). */
  private validateAt(moves: readonly Move[], i: number): ValidatedMove {
    try {
      return this.validate(moves[i]);
    } catch (err) {
      throw err instanceof MaxlError ? errorAt(err, `moves[${i}]`) : err;
    }
  }

  /** Turns a move into segments at the tail and plans them; `added` collects them for an edit's report. */
  protected enqueue(move: ValidatedMove, moveId: number, added: Segment[] | null): MoveReceipt {
    if (added === null && this.columnar && move.dwell_s === null && this.listeners.length === 0) {
      const id = this.enqueueLine(move.end, move.maxVelocity, move.maxAcceleration, move.events, move.actuatorEnd, moveId);
      if (id > 0) return { moveId, segmentIds: [id], skipped: false };
      if (id === LINE_SKIPPED) return { moveId, segmentIds: [], skipped: true };
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
   * one-piece case (moves.ts), without making the object. The move is given by its
   * validated fields (ValidatedMove's): its end (the path's tail position from now
   * on), caps, event specs and actuators at the end. Returns the segment's id (> 0);
   * LINE_SKIPPED for a zero-length move that sets no event (counted, nothing
   * queued); LINE_NEEDS_OBJECT, with nothing changed, for one that sets events (a
   * 0-s dwell), which the object path makes.
   */
  private enqueueLine(
    end: number[],
    maxVelocity: number,
    maxAcceleration: number,
    events: readonly ResolvedEventSpec[],
    actuatorEnd: number[] | null,
    moveId: number,
  ): number {
    const tail = this.tail;
    const unit = tail.unit === this.unitBuffers[0] ? this.unitBuffers[1] : this.unitBuffers[0];
    // moves.ts directionInto, written out here: the engine does not inline it at this depth,
    // and a length returned from a call is a number allocated on the heap per segment.
    const from = tail.position;
    let d2 = 0;
    for (let i = 0; i < from.length; i++) {
      const d = end[i] - from[i];
      d2 += d * d;
    }
    const length = Math.sqrt(d2);
    for (let i = 0; i < from.length; i++) unit[i] = (end[i] - from[i]) / length;
    if (length < ZERO_LENGTH_MM) {
      if (events.length > 0) return LINE_NEEDS_OBJECT;
      this.skippedZeroLength++;
      return LINE_SKIPPED;
    }
    const limits = this.lineLimits;
    const cruise2 = floorCruise2(limits.cruise2(maxVelocity, unit), length, this.minSegmentDuration_s);
    const accel = limits.accel(maxAcceleration, unit);
    const maxEntry2 = limits.entryCap2(tail.unit, tail.cruise2, unit, cruise2);
    const id = this.nextSegmentId++;
    const position = tail.position;
    this.pending.push(id, moveId, end, maxVelocity, maxAcceleration, events, actuatorEnd, position, unit, cruise2, actuatorPosition(this.config.transforms, position));
    this.planner.append(length, accel, maxEntry2);
    tail.position = end;
    tail.unit = unit;
    tail.cruise2 = cruise2;
    return id;
  }

  /** Moves the columnar tail into `live` as objects, so that the untransmitted path is all objects. */
  protected materialize(): void {
    if (this.pending.size === 0) return;
    const segments = this.pending.takeAll(this.planner, this.untransmitted);
    for (let i = 0; i < segments.length; i++) this.live.push(segments[i]);
    this.untransmitted += segments.length;
  }

  // --- the planner's hand-off and telling listeners ---

  /** The planner's report of a final plan, by offset from the first untransmitted segment. */
  private onPlanned(offset: number): void {
    // In the columnar tail: the object, when made, is planned and timed from the planner's final plan.
    if (offset >= this.untransmitted) return;
    const seg = this.live[this.live.length - this.untransmitted + offset];
    seg.entry2 = this.planner.finalEntry2(offset);
    seg.exit2 = this.planner.finalExit2(offset);
    seg.time();
    if (seg.state === 'unplanned') {
      seg.state = 'planned';
      this.newlyPlanned.push(seg);
    }
  }

  protected flushPlanned(): void {
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

  protected emit(type: QueueEventType, segments: readonly Segment[]): void {
    if (segments.length === 0) return;
    const listeners = this.listeners;
    for (let i = 0; i < listeners.length; i++) listeners[i]({ type, segments });
  }

  protected wakeWaiters(): void {
    while (this.gate.waiting > 0 && this.hasRoom()) this.gate.admitNext();
  }
}
