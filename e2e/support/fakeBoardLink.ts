/**
 * A fake board's end of its port, in the fake boards' Node process
 * (fakeBoardsProcess.ts): bytes the opener wrote (fakePortStreams.ts) go into the
 * board's simulated link at the time they were written, and the bytes the board
 * sends go back over the WebSocket.
 *
 * How a chunk reaches its board on time. The boards' process shares the
 * machine's cores with the browser and whatever else runs; when it does not get
 * the CPU for a while, the bytes the author wrote meanwhile wait in its socket,
 * while the boards' simulated time (a PacedScheduler on the wall clock) stands
 * still. A chunk written at wall time w is due at virtual time v(w). When the
 * process runs again, the scheduler's wake first lets Node's event loop read
 * its sockets (`wakeAfterIo`): every chunk that arrived while it was held back
 * goes in at its own time before the simulation runs past it. Only a chunk that
 * comes while a wake runs timers, and was written before that wake began, finds
 * its time passed: it goes in at once and is counted (`late`, `worstLate_us`), so
 * that a run can tell whether the fake, rather than the author, could have made
 * a board late.
 */
import type { WebSocket } from 'ws';
import type { PacedScheduler } from '../../core/index.ts';
import type { Link } from '../../core/net/link.ts';
import { decodeStampedChunk } from './fakePortStreams.ts';

/**
 * Lateness below this is the clocks' resolution, not lateness: Chrome coarsens
 * performance.now() to 100 µs on a page that is not cross-origin isolated, and a
 * stamp and its check read two such clocks (µs).
 */
const CLOCK_RESOLUTION_US = 200;

/** The process's clock, µs: the boards' PacedScheduler's wall clock. */
function wallNow_us(): number {
  return performance.now() * 1000;
}

/**
 * The boards' PacedScheduler's wake: a timer, then setImmediate, which Node runs
 * after the event loop's poll phase has read every socket that has data; only
 * then does the wake run the simulation. (A timer alone runs in the loop's
 * timers phase, before the sockets are read.)
 */
export function wakeAfterIo(): (delay_ms: number, callback: () => void) => { cancel(): void } {
  return (delay_ms, callback) => {
    let cancelled = false;
    const handle = setTimeout(
      () =>
        setImmediate(() => {
          if (!cancelled) callback();
        }),
      delay_ms,
    );
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
   * The longest a reply waited for the boards' process, µs: how far the
   * simulation was behind its pace (the wall clock) when the board sent it
   * (only replies made while the scheduler runs the simulation; bytes a board
   * said before its port was opened go out at the open, and waited for nothing).
   * A real board answers at once; a fake one held back this long answers this
   * much later (acknowledgements included, which the author's streamer waits for).
   */
  worstReplyWait_us: number;
  /** how many replies waited over SLOW_REPLY_US (5 ms) */
  slowReplies: number;
}

/** A reply that waited longer than this for the boards' process is counted as slow (µs). */
const SLOW_REPLY_US = 5000;

/** Connects `link` (a board's simulated link, author's end) to the opener behind `socket`. */
export function connectBoard(link: Link, socket: WebSocket, scheduler: PacedScheduler): BoardTraffic {
  const counts: BoardTraffic = { chunks: 0, late: 0, worstLate_us: 0, replies: 0, worstReplyWait_us: 0, slowReplies: 0 };
  const writer = link.writable.getWriter();
  socket.on('message', (data: Buffer, isBinary: boolean) => {
    if (!isBinary) return socket.close(1003, 'a fake port carries binary chunks only');
    const { bytes, sentAt_ms } = decodeStampedChunk(new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
    // Epoch ms → this process's performance.now() µs → virtual time.
    const due = scheduler.virtualTimeAtWall((sentAt_ms - performance.timeOrigin) * 1000);
    counts.chunks++;
    const late = scheduler.now() - due;
    if (late > CLOCK_RESOLUTION_US) {
      counts.late++;
      counts.worstLate_us = Math.max(counts.worstLate_us, late);
    }
    scheduler.at(due, () => void writer.write(bytes).catch(() => undefined));
  });
  void (async () => {
    const reader = link.readable.getReader();
    for (;;) {
      const { value, done } = await reader.read().catch(() => ({ value: undefined, done: true }));
      if (done) break;
      if (!value) continue;
      // Copied: a link may hand out views of one buffer, and ws sends a view as it is.
      socket.send(Buffer.from(value));
      counts.replies++;
      if (!scheduler.driving) continue;
      const wait = scheduler.virtualTimeAtWall(wallNow_us()) - scheduler.now();
      counts.worstReplyWait_us = Math.max(counts.worstReplyWait_us, wait);
      if (wait > SLOW_REPLY_US) counts.slowReplies++;
    }
    socket.close(1000, 'the board closed its link');
  })();
  return counts;
}
