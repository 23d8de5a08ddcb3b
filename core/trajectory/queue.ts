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
 *
 * The queue is built in layers, one file each, each a class extending the one before:
 *   queueCore.ts     the segments held, appending, the planner's hand-off, listeners
 *   queueReading.ts  reading: segments, states, the transmitted horizon, event tracks
 *   tailEditing.ts   editing the untransmitted tail: cancel, replace, the replanning
 *   queue.ts         (this file) the executor's side: lock the front (transmitNext,
 *                    executeFrontNow), split it, brake to rest, retire what ran,
 *                    and rebuild the path after a stop (restartFrom)
 */
import { MaxlError } from '../errors.ts';
import { actuatorRate, ZERO_LENGTH_MM } from './moves.ts';
import type { PendingFront } from './pendingSegments.ts';
import { shouldDropSpent } from '../plan/spentPrefix.ts';
import { PHASE_STRIDE, TRAPEZOID_MAX_PHASES, writeTrapezoidOf } from '../plan/phases.ts';
import type { QueueEventType, QueueView } from './queueView.ts';
import type { Segment, SegmentState } from './segment.ts';
import { TailEditing } from './tailEditing.ts';
import { copySegment, pointPosition, rejoinSegment, remainderOf, type PathPoint } from './restart.ts';

export { MAX_LOOKAHEAD_SEGMENTS, type MoveReceipt, type QueueEvent, type QueueListener } from './queueCore.ts';
export type { QueueEventType, SegmentState };

/** The whole queue: owned by Maxl (appending, editing) and the streamer (executing); apps read it through QueueView. */
export class TrajectoryQueue extends TailEditing implements QueueView {
  /** executeFrontNow()'s reused buffers: the front's fields, and its packed timing when there is no history to write it into. */
  private readonly front: PendingFront = emptyFront(this.config.motionAxes.length);
  private readonly timingBuffer = new Float64Array(TRAPEZOID_MAX_PHASES * PHASE_STRIDE);

  // --- splitting the front, braking to rest ---

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

  // --- executing ---

  /**
   * Whether the first untransmitted segment's plan is final: more path appended
   * cannot change it, so locking it now gives the plan that waiting would.
   */
  get frontIsFinal(): boolean {
    return this.planner.isFinal(0);
  }

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
    f.entry2 = this.planner.frontSpeed2;
    this.pending.dropFront();
    f.exit2 = this.planner.lockFront();
    f.startTime_us = start_us;
    // Segment.time()'s trapezoid and duration, written into the history's ring (or a buffer) instead of a new array.
    let duration_s: number;
    if (this.history) {
      const a0 = f.actuatorStart;
      f.actuatorRate = a0.length > 0 ? actuatorRate(a0, f.actuatorEnd as number[], f.length) : a0;
      duration_s = this.history.pushLine(f, end.eventValues);
    } else {
      const last = (writeTrapezoidOf(this.timingBuffer, 0, f) - 1) * PHASE_STRIDE;
      duration_s = this.timingBuffer[last] + this.timingBuffer[last + 1];
    }
    end.lock(start_us + duration_s * 1e6, f.exit2, f.end, f.unit, f.cruise2);
    // Nothing before it is held any more (all ran), so live holds no segment out of path order.
    if (this.head === this.live.length && this.head > 0) {
      this.live.length = 0;
      this.head = 0;
    }
    this.flushPlanned();
    this.wakeWaiters();
    return duration_s;
  }

  /**
   * executeFrontNow() for the front segments while their plan is final, at most
   * `max` of them (a dry run taking a run: dryRun.ts), stopping at the first that is
   * not final or when nothing is queued. Each one's duration is added, in path
   * order, to `tally.duration_s` and counted in `tally.segments`: one call from the
   * dry run for the whole run, the loop and its checks here, next to the lock.
   */
  executeFinalRun(max: number, earliestStart_us: number, tally: { segments: number; duration_s: number }): void {
    for (let n = 0; n < max && this.planner.isFinal(0); n++) {
      const duration_s = this.executeFrontNow(earliestStart_us);
      if (duration_s < 0) return;
      tally.segments++;
      tally.duration_s += duration_s;
    }
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
}

/** A PendingFront to read the columnar front into (its fields are overwritten by each read). */
function emptyFront(axes: number): PendingFront {
  const zeros = () => new Array<number>(axes).fill(0);
  // (Its numeric fields start as non-integers, so that the engine keeps them as doubles from the first.)
  const x = 0.5;
  return { start: zeros(), end: zeros(), unit: zeros(), events: [], actuatorStart: [], actuatorEnd: null, actuatorRate: [], length: x, accel: x, cruise2: x, entry2: x, exit2: x, startTime_us: x };
}
