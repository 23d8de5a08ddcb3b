/**
 * The read-only face of the author's trajectory, for apps and the workbench
 * (`maxl.queue`, `maxl.history`).
 *
 * The trajectory queue (queue.ts) has one owner per role:
 *   - authoring (add, replace, cancel moves of the untransmitted tail) goes through
 *     `Maxl` (core/maxl.ts), which validates against the path as it will stand;
 *   - executing (lock the front, split it, retire what ran, brake to rest) is the
 *     streamer's and the runtime's, inside the core (net/streamer.ts, core/runtime.ts);
 *   - reading is this view: the segments ahead and their states, the transmitted
 *     horizon, the queue's events, and the as-planned history of what was sent.
 * Nothing reached through it can change the trajectory.
 */
import type { HistoricalSegment } from './history.ts';
import type { SegmentState } from './segment.ts';
import type { TrajectorySample } from './tracks.ts';
import type { Timing } from '../plan/phases.ts';
import { forwardingView } from './forwardingView.ts';

/** A segment as a reader sees it (segment.ts has the meaning of each field). */
export interface SegmentView {
  readonly id: number;
  /** The addSegmentToQueue call it came from (a move may become several segments). */
  readonly moveId: number;
  readonly state: SegmentState;
  readonly start: readonly number[];
  readonly end: readonly number[];
  readonly unit: readonly number[];
  /** mm */
  readonly length: number;
  /** mm along its move at which it starts. */
  readonly moveOffset: number;
  /** s a dwell holds its position; null for a line. */
  readonly dwell_s: number | null;
  readonly isDwell: boolean;
  readonly actuatorStart: readonly number[];
  readonly actuatorRate: readonly number[];
  /** s(t) as packed phases once planned; null before. */
  readonly timing: Timing | null;
  /** s; NaN before it is timed. */
  readonly duration_s: number;
  /** author µs; NaN until transmitted. */
  readonly startTime_us: number;
  readonly endTime_us: number;
  /** Every event channel's value as it begins; null until transmitted. */
  readonly eventsAtStart: readonly number[] | null;
}

export type QueueEventType = 'added' | 'planned' | 'replanned' | 'transmitted' | 'historical' | 'removed';

/** What changed: segments added, finally planned, made provisional again, transmitted, executed, or edited away. */
export interface QueueViewEvent {
  readonly type: QueueEventType;
  readonly segments: readonly SegmentView[];
}

export interface QueueView {
  /** Live segments in path order (a copy): transmitted ones not yet retired, then the untransmitted. */
  segments(): SegmentView[];
  /** Live segments held. */
  readonly size: number;
  /** Segments not yet transmitted (the editable tail). */
  readonly untransmittedCount: number;
  /** Untransmitted segments the queue holds before addSegmentToQueue waits. */
  readonly capacity: number;
  /** Whether addSegmentToQueue would append at once, without waiting for room. */
  hasRoom(): boolean;
  /** A live segment by id. */
  get(id: number): SegmentView | undefined;
  /** The i-th untransmitted segment (0 = the next to transmit). */
  untransmittedAt(i: number): SegmentView | undefined;
  /** The end of the path as appended so far (mm, motion axes). */
  readonly tailPosition: readonly number[];
  /** Author µs at which the transmitted (locked) path ends; −∞ before anything was transmitted. */
  readonly transmittedEnd_us: number;
  /** Whether the machine will still be moving at the end of the transmitted path. */
  readonly transmittedEndsMoving: boolean;
  /** Zero-length moves (setting no event) skipped so far. */
  readonly skippedZeroLength: number;
  /** Hears every change; returns the unsubscribe function. */
  subscribe(listener: (event: QueueViewEvent) => void): () => void;
}

/** The as-planned record of every transmitted segment, oldest first (history.ts), read-only. */
export interface HistoryView {
  /** Records kept at most; older ones are dropped. */
  readonly capacity: number;
  /** Author µs before which the history no longer holds the plan. */
  readonly horizon_us: number;
  /** Records pushed since the start (kept or dropped). */
  readonly pushed: number;
  /** Records held. */
  readonly size: number;
  /** The i-th record held, 0 the oldest, as a fresh plain object. */
  at(i: number): HistoricalSegment;
  /** Index of the record running at t_us, or −1. */
  indexAt(t_us: number): number;
  /** Every track at author time t_us, or null if nothing was transmitted. */
  sample(t_us: number): TrajectorySample | null;
  /** An event channel's value at t_us. */
  eventValue(channel: number, t_us: number): number;
}

/**
 * A view that forwards only QueueView's members to `queue`: what `maxl.queue` is, so
 * that an app holds no reference to the queue's editing or executing methods.
 */
export function readOnlyQueue(queue: QueueView): QueueView {
  return forwardingView(queue, {
    segments: 'method',
    size: 'value',
    untransmittedCount: 'value',
    capacity: 'value',
    hasRoom: 'method',
    get: 'method',
    untransmittedAt: 'method',
    tailPosition: 'value',
    transmittedEnd_us: 'value',
    transmittedEndsMoving: 'value',
    skippedZeroLength: 'value',
    subscribe: 'method',
  });
}

/** The same for the history: `maxl.history`. */
export function readOnlyHistory(history: HistoryView): HistoryView {
  return forwardingView(history, {
    capacity: 'value',
    horizon_us: 'value',
    pushed: 'value',
    size: 'value',
    at: 'method',
    indexAt: 'method',
    sample: 'method',
    eventValue: 'method',
  });
}
