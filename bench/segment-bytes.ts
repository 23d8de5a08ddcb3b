/**
 * Wire cost of a linear segment, for `npm run bench -- firmware` (which merges
 * this script's last JSON line) and on its own: `npx tsx bench/segment-bytes.ts`.
 *
 * The planner's three benchmark paths are planned and timed by the core, then
 * encoded for a device that reads one position track (GEOMETRY + TIMING, batched
 * as a session streams them). bytesPerLinearSegment = payload bytes per segment per
 * position track (the protocol's budget is 24; the public MAXL prototype used 52).
 * Framing (seq, type, CRC, COBS, delimiter) is reported separately.
 */
import { createMAXL, type SegmentView } from '../core/index.ts';
import { ClockMap } from '../core/net/clockMap.ts';
import { encodeFrame } from '../core/net/frame.ts';
import { encodePayload } from '../core/net/messages.ts';
import { geometryMessages, timingMessages } from '../core/net/segmentEncoding.ts';
import { benchPaths, BENCH_LIMITS } from './paths.ts';
import { queueOf } from '../core/maxl.ts';

const COUNT = Number(process.env.SEGMENTS ?? 100_000);
/** Segments per streamed batch: a session sends a few at a time, just in time. */
const BATCH = 8;

const perPath: Record<string, { segments: number; payloadBytesPerSegment: number; framedBytesPerSegment: number }> = {};
let worst = 0;
for (const path of benchPaths(COUNT)) {
  const maxl = createMAXL({ motionAxes: ['x', 'y'], limits: BENCH_LIMITS }, { initialPosition: path.start, historyLimit: 1 });
  for (const p of path.points) queueOf(maxl).append({ endPosition: p });
  queueOf(maxl).planToRest();
  const clock = new ClockMap(0, 12345, 1.0001);
  let payload = 0;
  let framed = 0;
  let segments = 0;
  let batch: SegmentView[] = [];
  const flush = () => {
    const first = segments - batch.length + 1;
    const messages = [...geometryMessages(batch, [{ space: 'motion', index: 0 }], first, first === 1), ...timingMessages(batch, clock, first, first === 1, 3000)];
    for (const m of messages) {
      payload += encodePayload(m).length;
      framed += encodeFrame(0, m).length;
    }
    batch = [];
  };
  for (let s = queueOf(maxl).transmitNext(0); s; s = queueOf(maxl).transmitNext(0)) {
    batch.push(s);
    segments++;
    if (batch.length === BATCH) flush();
    queueOf(maxl).retireUntil(s.startTime_us);
  }
  if (batch.length) flush();
  perPath[path.name] = { segments, payloadBytesPerSegment: +(payload / segments).toFixed(2), framedBytesPerSegment: +(framed / segments).toFixed(2) };
  worst = Math.max(worst, payload / segments);
}
console.log(JSON.stringify({ bytesPerLinearSegment: +worst.toFixed(2), bytesLimit: 24, positionTracks: 1, batch: BATCH, paths: perPath }));
