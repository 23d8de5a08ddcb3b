/**
 * Editing the trajectory queue's untransmitted tail: cancel or replace a move,
 * cancel from a move or segment on, and the replanning every edit opens and
 * settles with (reopenPlanFrom, settleReplan). Transmitted segments are locked:
 * editing one is refused (SEGMENT_LOCKED). An edit the moving machine could no
 * longer brake for is refused with nothing changed (CANNOT_STOP_IN_PATH).
 *
 * The executor's split and braking (queue.ts: splitFront, brakeToRest) edit the
 * tail in place through splitAt and restBefore here. Authoring reaches these
 * through Maxl (core/maxl.ts), which validates moves against the path as it will
 * stand.
 */
import { MaxlError } from '../errors.ts';
import { tailAfter, type Move, type ValidatedMove } from './moves.ts';
import type { MoveReceipt } from './queueCore.ts';
import { QueueReading } from './queueReading.ts';
import { Segment } from './segment.ts';

const LOCKED_MESSAGE = 'has already been transmitted; transmitted segments are locked';

/** QueueReading with the editing of the untransmitted tail; TrajectoryQueue (queue.ts) is the whole queue. */
export abstract class TailEditing extends QueueReading {
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

  /** Makes live[index] start from rest (its entry cap 0), replanning from there. */
  protected restBefore(index: number): Segment {
    const seg = this.live[index];
    this.replanFrom(index, () => {
      seg.maxEntry2 = 0;
    });
    return seg;
  }

  /** Splits live[index] at `distance`; with `rest`, the second piece starts from rest. */
  protected splitAt(index: number, distance: number, rest: boolean): [Segment, Segment] {
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
}
