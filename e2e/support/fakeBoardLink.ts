/**
 * A fake board's end of its port, in the fake boards' worker: bytes the opener
 * wrote (fakePortStreams.ts) go into the board's simulated link at the time they
 * were written, and the bytes the board sends go back over the channel.
 *
 * How a chunk reaches its board on time. The boards' worker shares the browser's
 * two cores with the author; when it does not get the CPU for a while, the bytes
 * the author wrote meanwhile wait in its message queue, while the boards'
 * simulated time (a PacedScheduler on the wall clock) stands still. A chunk
 * written at wall time w is due at virtual time v(w). When the worker runs again,
 * the scheduler's wake first lets the message queue go round once
 * (`wakeAfterMail`): every chunk that arrived while it was held back goes in at
 * its own time before the simulation runs past it. Only a chunk that comes while
 * a wake runs timers, and was written before that wake began, finds its time
 * passed: it goes in at once and is counted (`late`, `worstLate_us`), so that a
 * run can tell whether the fake, rather than the author, could have made a board
 * late. (A fixed lag of the boards' clock behind the wall, which an earlier
 * version had, changed nothing: the chunks' times and the simulation's moved by
 * the same amount.)
 */
import type { PacedScheduler } from '../../core/index.ts';
import type { Link } from '../../core/net/link.ts';
import type { ChannelClosed, StampedChunk } from './fakePortStreams.ts';

/**
 * Lateness below this is the clocks' resolution, not lateness: Chrome coarsens
 * performance.now() to 100 µs on a page that is not cross-origin isolated, and a
 * stamp and its check read two such clocks (µs).
 */
const CLOCK_RESOLUTION_US = 200;

/** The worker's clock, µs: the boards' PacedScheduler's wall clock. */
function wallNow_us(): number {
  return performance.now() * 1000;
}

/**
 * The boards' PacedScheduler's wake: a timer, then one turn of the worker's
 * message queue (a message to itself, which queues behind every message already
 * there), then the wake runs the simulation.
 */
export function wakeAfterMail(): (delay_ms: number, callback: () => void) => { cancel(): void } {
  const turn = new MessageChannel();
  const waiting: Array<() => void> = [];
  turn.port1.onmessage = () => waiting.shift()?.();
  return (delay_ms, callback) => {
    let cancelled = false;
    const handle = setTimeout(() => {
      waiting.push(() => {
        if (!cancelled) callback();
      });
      turn.port2.postMessage(0);
    }, delay_ms);
    return {
      cancel: () => {
        cancelled = true;
        clearTimeout(handle);
      },
    };
  };
}

export interface BoardTraffic {
  /** chunks the opener wrote */
  chunks: number;
  /** of them, how many reached the board's link after their time (by more than the clocks' resolution) */
  late: number;
  /** the latest of those, µs after its time */
  worstLate_us: number;
  /** chunks the board sent back */
  replies: number;
  /**
   * The longest a reply waited for the boards' worker, µs: how far the simulation
   * was behind its pace (the wall clock) when the board sent it. A real
   * board answers at once; a fake one held back this long answers this much later
   * (acknowledgements included, which the author's streamer waits for).
   */
  worstReplyWait_us: number;
}

/** Connects `link` (a board's simulated link, author's end) to the opener behind `channel`. */
export function connectBoard(link: Link, channel: MessagePort, scheduler: PacedScheduler): BoardTraffic {
  const counts: BoardTraffic = { chunks: 0, late: 0, worstLate_us: 0, replies: 0, worstReplyWait_us: 0 };
  const writer = link.writable.getWriter();
  channel.onmessage = (m: MessageEvent<StampedChunk>) => {
    const { bytes, sentAt_ms } = m.data;
    // Epoch ms → this worker's performance.now() µs → virtual time.
    const due = scheduler.virtualTimeAtWall((sentAt_ms - performance.timeOrigin) * 1000);
    counts.chunks++;
    const late = scheduler.now() - due;
    if (late > CLOCK_RESOLUTION_US) {
      counts.late++;
      counts.worstLate_us = Math.max(counts.worstLate_us, late);
    }
    scheduler.at(due, () => void writer.write(bytes).catch(() => undefined));
  };
  void (async () => {
    const reader = link.readable.getReader();
    for (;;) {
      const { value, done } = await reader.read().catch(() => ({ value: undefined, done: true }));
      if (done) break;
      // Copied, not transferred: a link may hand out views of one buffer.
      if (!value) continue;
      channel.postMessage(value);
      counts.replies++;
      counts.worstReplyWait_us = Math.max(counts.worstReplyWait_us, scheduler.virtualTimeAtWall(wallNow_us()) - scheduler.now());
    }
    channel.postMessage({ closed: true } satisfies ChannelClosed);
  })();
  return counts;
}
