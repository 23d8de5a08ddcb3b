/**
 * TIMING for one device's timed path, as the streamer sends it: newly timed
 * segments are grouped in runs of contiguous ones (each starts exactly where the
 * device's timed path ends, in author time), and a segment after rest starts a
 * new run with an explicit start (segmentEncoding.ts timingMessages).
 */
import type { ClockMap } from './clockMap.ts';
import type { MessageOf } from './messages.ts';
import { timingMessages, type EncodableSegment } from './segmentEncoding.ts';

/** Where a device's timed path ends: device µs (exact, unwrapped; null before any timing) and the author µs it stands for. */
export interface TimedPathEnd {
  timedEnd: number | null;
  timedEndAuthor: number;
}

export interface TimedSegment extends EncodableSegment {
  endTime_us: number;
}

/**
 * The TIMING messages for `segs` (in order, each newly timed), with each one's
 * length on the device's timeline (whole µs, for its events). Moves `path` to
 * the end of the last one.
 */
export function timingForPath<S extends TimedSegment>(
  path: TimedPathEnd,
  segs: readonly S[],
  clock: ClockMap,
  wireId: (seg: S) => number,
  stopDecel: number,
): { messages: MessageOf<'TIMING'>[]; deviceLengths: number[] } {
  const messages: MessageOf<'TIMING'>[] = [];
  const deviceLengths: number[] = [];
  let run: S[] = [];
  let runStart = false;
  const flush = () => {
    if (run.length === 0) return;
    const batch = timingMessages(run, clock, wireId(run[0]), runStart, stopDecel, path.timedEnd ?? undefined);
    path.timedEnd = batch.end ?? path.timedEnd;
    messages.push(...batch);
    for (const span of batch.spans) deviceLengths.push(span.length);
    run = [];
  };
  for (const seg of segs) {
    const contiguous = path.timedEnd !== null && seg.startTime_us === path.timedEndAuthor;
    if (run.length === 0 || !contiguous) {
      flush();
      runStart = !contiguous;
    }
    run.push(seg);
    path.timedEndAuthor = seg.endTime_us;
  }
  flush();
  return { messages, deviceLengths };
}
