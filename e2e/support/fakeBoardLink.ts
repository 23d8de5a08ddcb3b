/**
 * A fake board's end of its port, in the fake boards' worker: bytes the opener
 * wrote (fakePortStreams.ts) go into the board's simulated link at the time they
 * were written, and the bytes the board sends go back over the channel.
 *
 * Why the boards trail the wall clock. The boards' worker shares the browser's
 * two cores with the author; when it does not get the CPU for a while, the bytes
 * the author wrote meanwhile wait in its message queue. The boards' simulated
 * time therefore trails the wall clock by BOARD_LAG_US (their PacedScheduler's
 * wall clock is shifted back by that much): a chunk written at wall time w is
 * due at virtual time v(w − lag), and the simulation has not passed it unless the
 * worker was held back for longer than the lag. A constant offset between a
 * board's clock and the author's is what clock sync measures anyway, and the
 * board still answers a PING one link delay after it was sent (the simulation
 * reaches v(w − lag) at wall time w), so the round trips it shows stay those of
 * the link model.
 *
 * A chunk that does arrive after its time (the worker held back longer than the
 * lag) goes in at once, and is counted: `late` and `worstLate_us` say whether the
 * fake, rather than the author, could have made a board late.
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

/** How far the fake boards' simulated time trails the wall clock, µs. */
export const BOARD_LAG_US = 250_000;

/** The boards' wall clock (µs), shifted back by the lag: give it to their PacedScheduler. */
export function laggedWallNow(): number {
  return performance.now() * 1000 - BOARD_LAG_US;
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
   * was behind its pace (the lagged wall clock) when the board sent it. A real
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
    // Epoch ms → this worker's performance.now() µs → the lagged wall clock → virtual time.
    const due = scheduler.virtualTimeAtWall((sentAt_ms - performance.timeOrigin) * 1000 - BOARD_LAG_US);
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
      counts.worstReplyWait_us = Math.max(counts.worstReplyWait_us, scheduler.virtualTimeAtWall(laggedWallNow()) - scheduler.now());
    }
    channel.postMessage({ closed: true } satisfies ChannelClosed);
  })();
  return counts;
}
