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
 * The queue is bounded: it holds at most `capacity` untransmitted segments, and
 * producers wait for room (waitForRoom), so a loop of addSegmentToQueue calls
 * paces itself to the machine. An executor (the device sessions, or a dry run)
 * takes segments from the front with transmitNext() and retires them with
 * retireUntil() as time passes.
 */
import { MaxlError } from '../errors.ts';
import type { ResolvedConfig } from '../config/types.ts';
import { LookaheadPlanner } from '../plan/lookahead.ts';
import { buildEventTracks, type EventTrack } from './events.ts';
import { segmentsForMove, validateMove, type Move, type PathTail, type ValidatedMove } from './moves.ts';
import { Segment, type SegmentState } from './segment.ts';

export type QueueEventType = 'added' | 'planned' | 'replanned' | 'transmitted' | 'historical' | 'removed';

export interface QueueEvent {
  type: QueueEventType;
  segments: readonly Segment[];
}

export type QueueListener = (event: QueueEvent) => void;

export interface MoveReceipt {
  moveId: number;
  /** The segments the move became: one, or several when a nonlinear transform subdivided it. */
  segmentIds: number[];
  /** True for a zero-length move, which adds nothing. */
  skipped: boolean;
}

/** A move's record while any of its segments is untransmitted. */
interface QueuedMove {
  moveId: number;
  move: ValidatedMove;
  segments: Segment[];
}

export const DEFAULT_QUEUE_CAPACITY = 512;

export class TrajectoryQueue {
  readonly config: ResolvedConfig;
  readonly capacity: number;
  /** Zero-length moves skipped so far. */
  skippedZeroLength = 0;

  /** Live segments (unplanned, planned, transmitted) in path order; live[head] is the oldest. */
  private live: Segment[] = [];
  private head = 0;
  private untransmitted = 0;
  /** Moves with untransmitted segments, oldest first. */
  private moves: QueuedMove[] = [];
  private readonly planner: LookaheadPlanner<Segment>;
  /** Segments finalised during the current call, reported once it returns. */
  private newlyPlanned: Segment[] = [];
  private nextSegmentId = 1;
  private nextMoveId = 1;
  /** End of the path as appended so far. */
  private tail: PathTail;
  /** End of the last transmitted segment: author µs, and whether the machine is still moving there. */
  private lockedEnd_us = -Infinity;
  private lockedExit2 = 0;
  /** Event channel values at the end of the transmitted path. */
  private lockedEventValues: number[];
  private listeners = new Set<QueueListener>();
  /** Producers waiting for room, oldest first, and slots promised to woken ones. */
  private roomWaiters: Array<() => void> = [];
  private reserved = 0;
  private readonly eventTracks = new WeakMap<Segment, EventTrack[]>();
  private readonly eventsAtStart = new WeakMap<Segment, number[]>();

  constructor(config: ResolvedConfig, initialPosition?: number[]) {
    this.config = config;
    this.capacity = config.queueCapacity;
    const position = initialPosition ? [...initialPosition] : new Array<number>(config.motionAxes.length).fill(0);
    this.tail = { position, unit: null, cruise2: 0 };
    this.lockedEventValues = new Array<number>(config.eventChannels.length).fill(0);
    this.planner = new LookaheadPlanner<Segment>((seg) => this.onPlanned(seg));
  }

  // --- reading ---

  /** Live segments in path order (a copy). */
  segments(): Segment[] {
    return this.live.slice(this.head);
  }

  get size(): number {
    return this.live.length - this.head;
  }

  get untransmittedCount(): number {
    return this.untransmitted;
  }

  hasRoom(): boolean {
    return this.untransmitted + this.reserved < this.capacity;
  }

  /** The end of the path as appended so far (mm, motion axes). */
  get tailPosition(): readonly number[] {
    return this.tail.position;
  }

  /** Author µs at which the transmitted path ends. −∞ before anything is transmitted. */
  get transmittedEnd_us(): number {
    return this.lockedEnd_us;
  }

  /** Whether the machine will still be moving at the end of the transmitted path. */
  get transmittedEndsMoving(): boolean {
    return this.lockedExit2 > 0;
  }

  get(id: number): Segment | undefined {
    // Ids rise along the queue, so a binary search finds one.
    let lo = this.head;
    let hi = this.live.length - 1;
    while (lo <= hi) {
      const mid = (lo + hi) >> 1;
      const s = this.live[mid];
      if (s.id === id) return s;
      if (s.id < id) lo = mid + 1;
      else hi = mid - 1;
    }
    return undefined;
  }

  /** The first segment not yet transmitted, if any. */
  peekUntransmitted(): Segment | undefined {
    return this.untransmitted > 0 ? this.planner.at(0) : undefined;
  }

  /**
   * Fills in the provisional speeds of unplanned segments (as if the path ended
   * at rest now), for display. Final plans are untouched.
   */
  provisionalPlan(): void {
    this.planner.fillProvisional();
  }

  /**
   * A segment's event tracks, sampled from its evaluators. Built once its timing is
   * final; throws the evaluator's MaxlError if one failed.
   */
  eventTracksOf(seg: Segment): EventTrack[] {
    let tracks = this.eventTracks.get(seg);
    if (tracks === undefined) {
      if (seg.phases === null) throw new MaxlError('SEGMENT_NOT_FOUND', `segment ${seg.id} is not timed yet`);
      const timed = { ...seg, phases: seg.phases, length: seg.length, moveOffset: seg.moveOffset, start: seg.start, unit: seg.unit };
      tracks = buildEventTracks(seg.events, timed, this.config.motionAxes, this.config.actuatorAxes, this.config.eventChannels);
      this.eventTracks.set(seg, tracks);
    }
    return tracks;
  }

  /** Every event channel's value as a transmitted segment begins (index = channel). */
  eventValuesAtStart(seg: Segment): readonly number[] | undefined {
    return this.eventsAtStart.get(seg);
  }

  subscribe(listener: QueueListener): () => void {
    this.listeners.add(listener);
    return () => this.listeners.delete(listener);
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
  reserveSlot(): Promise<void> {
    if (this.hasRoom() && this.roomWaiters.length === 0) {
      this.reserved++;
      return Promise.resolve();
    }
    return new Promise((resolve) => this.roomWaiters.push(resolve));
  }

  /**
   * Appends a validated move now. `reserved` says the caller holds a slot from
   * reserveSlot(); without one the move is appended whether or not there is room.
   */
  appendValidated(move: ValidatedMove, reserved = false): MoveReceipt {
    if (reserved) this.reserved--;
    const moveId = this.nextMoveId++;
    const segments = segmentsForMove(this.config, move, this.tail, { nextSegmentId: this.nextSegmentId, moveId });
    if (segments.length === 0) {
      this.skippedZeroLength++;
      return { moveId, segmentIds: [], skipped: true };
    }
    this.nextSegmentId += segments.length;
    this.moves.push({ moveId, move, segments });
    for (const seg of segments) {
      this.live.push(seg);
      this.untransmitted++;
      this.planner.append(seg);
    }
    const last = segments[segments.length - 1];
    this.tail = { position: last.end, unit: last.unit, cruise2: last.cruise2 };
    this.emit('added', segments);
    this.flushPlanned();
    return { moveId, segmentIds: segments.map((s) => s.id), skipped: false };
  }

  /** Validates and appends in one step, ignoring the capacity bound. */
  append(move: Move): MoveReceipt {
    return this.appendValidated(this.validate(move));
  }

  // --- editing ---

  /** Cancels an untransmitted move (all its segments). Later moves now start where the one before it ended. */
  cancel(moveId: number): void {
    this.edit(moveId, null);
  }

  /** Replaces an untransmitted move by another. Later moves keep their end positions. */
  replace(moveId: number, move: Move): MoveReceipt {
    return this.edit(moveId, move) as MoveReceipt;
  }

  /** Cancels every untransmitted move. */
  cancelAll(): void {
    if (this.moves.length > 0) this.edit(this.moves[0].moveId, null, true);
  }

  private findMove(moveId: number): number {
    const index = this.moves.findIndex((m) => m.moveId === moveId);
    if (index >= 0) {
      if (this.moves[index].segments.some((s) => s.locked)) {
        throw new MaxlError('SEGMENT_LOCKED', `move ${moveId} has already been transmitted; transmitted segments are locked`);
      }
      return index;
    }
    const seg = this.live.slice(this.head).find((s) => s.moveId === moveId);
    if (seg || moveId < this.nextMoveId) {
      throw new MaxlError('SEGMENT_LOCKED', `move ${moveId} has already been transmitted; transmitted segments are locked`);
    }
    throw new MaxlError('SEGMENT_NOT_FOUND', `there is no move ${moveId}`);
  }

  private edit(moveId: number, replacement: Move | null, toEnd = false): MoveReceipt | undefined {
    const index = this.findMove(moveId);
    const edited = this.moves[index];
    const firstSeg = edited.segments[0];
    const planIndex = this.live.indexOf(firstSeg, this.head) - (this.live.length - this.untransmitted);
    const startPos = firstSeg.start;
    // Validate the replacement before touching anything.
    const validated = replacement ? this.validate(replacement, startPos) : null;

    const keptMoves = this.moves.slice(0, index);
    const laterMoves = toEnd ? [] : this.moves.slice(index + 1);
    const oldMoves = this.moves.slice(index);
    const oldTail = this.tail;
    // Every untransmitted segment is replanned; onPlanned marks the final ones again.
    const wasPlanned = this.untransmittedSegments().filter((seg) => seg.state === 'planned');
    for (const seg of this.untransmittedSegments()) seg.state = 'unplanned';
    this.newlyPlanned = [];
    const removed = this.planner.truncate(planIndex);
    this.live.length -= removed.length;
    this.untransmitted -= removed.length;
    for (const s of removed) s.state = 'unplanned';
    this.moves = keptMoves;
    const before = this.live[this.live.length - 1];
    this.tail = before
      ? { position: before.end, unit: before.unit, cruise2: before.cruise2 }
      : { position: [...startPos], unit: null, cruise2: 0 };

    const added: Segment[] = [];
    let receipt: MoveReceipt | undefined;
    const requeue = (move: ValidatedMove, id?: number): MoveReceipt => {
      const moveIdUsed = id ?? this.nextMoveId++;
      const segs = segmentsForMove(this.config, move, this.tail, { nextSegmentId: this.nextSegmentId, moveId: moveIdUsed });
      if (segs.length === 0) {
        this.skippedZeroLength++;
        return { moveId: moveIdUsed, segmentIds: [], skipped: true };
      }
      this.nextSegmentId += segs.length;
      this.moves.push({ moveId: moveIdUsed, move, segments: segs });
      for (const seg of segs) {
        this.live.push(seg);
        this.untransmitted++;
        this.planner.append(seg);
        added.push(seg);
      }
      const last = segs[segs.length - 1];
      this.tail = { position: last.end, unit: last.unit, cruise2: last.cruise2 };
      return { moveId: moveIdUsed, segmentIds: segs.map((s) => s.id), skipped: false };
    };
    if (validated) receipt = requeue(validated);
    for (const m of laterMoves) requeue(m.move, m.moveId);

    if (!this.planner.isFeasible()) {
      // Undo: the machine is already committed to a speed this path cannot absorb.
      this.planner.truncate(planIndex);
      this.live.length -= added.length;
      this.untransmitted -= added.length;
      this.moves = keptMoves.concat(oldMoves);
      for (const seg of removed) {
        this.live.push(seg);
        this.untransmitted++;
        this.planner.append(seg);
      }
      this.tail = oldTail;
      this.settleReplan(wasPlanned);
      throw new MaxlError(
        'CANNOT_STOP_IN_PATH',
        'the machine is already committed to a speed that this change would not leave room to brake from; stop the machine first, or edit moves further ahead',
      );
    }
    this.settleReplan(wasPlanned);
    if (removed.length > 0) this.emit('removed', removed);
    if (added.length > 0) this.emit('added', added);
    this.flushPlanned();
    this.wakeWaiters();
    return receipt;
  }

  private untransmittedSegments(): Segment[] {
    return this.live.slice(this.live.length - this.untransmitted);
  }

  /**
   * After an edit replanned the untransmitted segments: those that were planned
   * and no longer are lose their timing and are reported as 'replanned'; only
   * segments that became planned are reported as 'planned'.
   */
  private settleReplan(wasPlanned: Segment[]): void {
    const before = new Set(wasPlanned);
    const dropped = wasPlanned.filter((seg) => seg.state === 'unplanned' && this.live.includes(seg));
    for (const seg of dropped) {
      seg.phases = null;
      this.eventTracks.delete(seg);
    }
    this.newlyPlanned = this.newlyPlanned.filter((seg) => !before.has(seg));
    if (dropped.length > 0) this.emit('replanned', dropped);
  }

  // --- executing ---

  /**
   * Locks the first untransmitted segment and gives it its start time in author µs:
   * right after the transmitted path if the machine is still moving there, else at
   * `earliestStart_us` or later. Returns undefined when nothing is queued.
   * Throws the MaxlError of a failed event evaluator, leaving the segment queued.
   */
  transmitNext(earliestStart_us: number): Segment | undefined {
    if (this.untransmitted === 0) return undefined;
    const next = this.planner.at(0);
    if (next.state !== 'planned') {
      // Time it with the exit speed locking will give it, so that a failing event
      // evaluator throws before anything is locked.
      next.exit2 = this.planner.frontExit2();
      next.time();
      this.eventTracks.delete(next);
    }
    this.eventTracksOf(next);
    const seg = this.planner.lockFront();
    const contiguous = this.lockedExit2 > 0;
    seg.startTime_us = contiguous ? this.lockedEnd_us : Math.max(earliestStart_us, this.lockedEnd_us);
    seg.state = 'transmitted';
    this.untransmitted--;
    this.lockedEnd_us = seg.endTime_us;
    this.lockedExit2 = seg.exit2;
    this.eventsAtStart.set(seg, this.lockedEventValues);
    const tracks = this.eventTracksOf(seg);
    if (tracks.length > 0) {
      const values = [...this.lockedEventValues];
      for (const t of tracks) values[t.channel] = t.values[t.values.length - 1];
      this.lockedEventValues = values;
    }
    const move = this.moves[0];
    if (move && move.segments[move.segments.length - 1] === seg) this.moves.shift();
    this.emit('transmitted', [seg]);
    this.flushPlanned();
    this.wakeWaiters();
    return seg;
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
    const retired: Segment[] = [];
    while (this.head < this.live.length) {
      const seg = this.live[this.head];
      if (seg.state !== 'transmitted' || seg.endTime_us > now_us) break;
      seg.state = 'historical';
      retired.push(seg);
      this.head++;
    }
    if (this.head > 1024 && this.head * 2 > this.live.length) {
      this.live = this.live.slice(this.head);
      this.head = 0;
    }
    if (retired.length > 0) this.emit('historical', retired);
    return retired;
  }

  // --- internals ---

  private onPlanned(seg: Segment): void {
    seg.time();
    this.eventTracks.delete(seg);
    if (seg.state === 'unplanned') {
      seg.state = 'planned';
      this.newlyPlanned.push(seg);
    }
  }

  private flushPlanned(): void {
    if (this.newlyPlanned.length === 0) return;
    const planned = this.newlyPlanned;
    this.newlyPlanned = [];
    if (this.listeners.size > 0) this.emit('planned', planned.filter((s) => s.state === 'planned'));
  }

  private emit(type: QueueEventType, segments: readonly Segment[]): void {
    if (segments.length === 0) return;
    for (const listener of this.listeners) listener({ type, segments });
  }

  private wakeWaiters(): void {
    while (this.roomWaiters.length > 0 && this.hasRoom()) {
      const resolve = this.roomWaiters.shift() as () => void;
      this.reserved++;
      resolve();
    }
  }
}

export type { SegmentState };
