/**
 * The trajectory queue's reading side: the live segments and their states, the
 * path's tail, the transmitted horizon, provisional speeds for display, a
 * segment's event tracks, and listening to the queue's events. These are the
 * members `maxl.queue` forwards (queueView.ts), and what the executor reads
 * before it locks a segment. Reading the untransmitted path as objects first makes
 * the columnar tail into objects (materialize, queueCore.ts).
 */
import { MaxlError } from '../errors.ts';
import { buildEventTracks, type EventTrack } from './events.ts';
import { QueueCore, type QueueListener } from './queueCore.ts';
import type { Segment } from './segment.ts';

/** The tracks of a segment that sets no event channel. */
const NO_EVENTS: EventTrack[] = [];

/** QueueCore with its reading methods; TrajectoryQueue (queue.ts) is the whole queue. */
export abstract class QueueReading extends QueueCore {
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
