/**
 * A dry run: an executor with no device, for benches and tests that plan through
 * the queue and want what a machine would run, as fast as the planner goes.
 *
 * It locks segments from the front and retires them at once, as if each had been
 * executed the moment it was sent (time runs as fast as the plan is made), so the
 * queue never holds more than planning needs. Like a device session it takes a
 * segment only when it must: while the queue has no room for the producer
 * (`takeWhileFull`, after each add; a run of final segments at once if asked), and at the end, with the plan brought to
 * rest (`finish`). A queue that waits for room therefore hands it only segments
 * whose plan is final (TrajectoryQueue.hasRoom), and the dry run's total duration
 * is the time-optimal one planPath gives for the same path.
 */
import type { TrajectoryQueue } from './queue.ts';
import type { Segment } from './segment.ts';

export class DryRun {
  private readonly queue: TrajectoryQueue;
  private readonly onSegment: ((seg: Segment) => void) | undefined;
  /** Segments taken so far. */
  segments = 0;
  /** s, the sum of the durations of the segments taken. */
  duration_s = 0;

  /** `onSegment` hears of each segment as it is taken (locked, timed and retired). */
  constructor(queue: TrajectoryQueue, onSegment?: (seg: Segment) => void) {
    this.queue = queue;
    this.onSegment = onSegment;
  }

  /** Takes the front segment: locks it, retires it, and returns it; undefined if none is queued. */
  takeFront(): Segment | undefined {
    const seg = this.queue.transmitNext(0);
    if (seg === undefined) return undefined;
    // Executed as soon as it is sent: it, and everything before it, is history now.
    this.queue.retireUntil(seg.endTime_us);
    this.segments++;
    this.duration_s += seg.duration_s;
    this.onSegment?.(seg);
    return seg;
  }

  /**
   * Takes segments until the producer has room again (what a producer loop calls
   * after each add). With `chunk` > 1, once it had to take one, it goes on taking
   * while the front's plan is final (TrajectoryQueue.frontIsFinal) until the queue
   * has room for `chunk` more segments below its capacity: as a device streamer
   * fills a board's buffer in runs, so that a producer (single adds or
   * addSegmentsNow) appends runs of moves, not one at a time. Locking a final segment changes no
   * plan, so the segments taken, and their plan, are the same for every chunk.
   */
  takeWhileFull(chunk = 1): void {
    const q = this.queue;
    if (q.hasRoom()) return;
    while (!q.hasRoom() && this.take());
    const keep = q.capacity - chunk;
    const more = q.untransmittedCount - keep;
    if (more <= 0) return;
    if (this.onSegment) {
      for (let n = 0; n < more && q.frontIsFinal && this.take(); n++);
    } else {
      q.executeFinalRun(more, 0, this);
    }
  }

  /** The path is complete: plans it to rest and takes every queued segment. */
  finish(): void {
    this.queue.planToRest();
    while (this.take());
    this.queue.retireUntil(this.queue.transmittedEnd_us);
  }

  /**
   * Takes the front segment; false if none is queued. Without `onSegment` nobody
   * needs it as an object, so the queue may lock and record it from its columns
   * (TrajectoryQueue.executeFrontNow).
   */
  private take(): boolean {
    if (this.onSegment) return this.takeFront() !== undefined;
    const duration_s = this.queue.executeFrontNow(0);
    if (duration_s < 0) return false;
    this.segments++;
    this.duration_s += duration_s;
    return true;
  }
}
