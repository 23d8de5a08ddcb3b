/**
 * Keeps a job within what each link carries.
 *
 * The streamer sends each segment's GEOMETRY and TIMING to every device that reads
 * one of its position tracks, a little before the segment starts (streamer.ts).
 * If a segment costs b bytes on a link that carries B bytes/s, the segments must
 * last b/B each, on average, or the stream falls further behind its lead with every
 * segment until the device runs out of timing and brakes to a stop (starvation).
 * An Uno is the common case: its ATmega328P hears the host through a 250 000 baud
 * UART, 25 kB/s, while a 250 mm/s fine spiral (0.2 mm segments, ~30 bytes each to
 * a two-motor board) needs ~37 kB/s.
 *
 * So every segment gets a floor on its duration, T = b / (B · LINK_SHARE), taken
 * over the devices (the slowest link and the widest subscription decide). The rest
 * of the link is for PINGs (one every 4–25 ms), EVENTS and resends. The planner
 * turns the floor into a speed cap (trajectory/moves.ts): a segment of length L
 * whose speed never exceeds L/T lasts at least T, because its duration is L over
 * its mean speed, and the mean is at most the maximum.
 *
 * b is counted with the real encoders and framing: the GEOMETRY and TIMING frames
 * of a batch of SEGMENTS_PER_FRAME short segments (durations under 16 ms, whose
 * varints take 2 bytes; longer segments are far from the floor), divided by the
 * batch. Event tracks are not counted: an event-heavy job (a dense light-painting
 * bitmap) can still need more than this leaves.
 */
import { trapezoidTiming } from '../plan/phases.ts';
import { ClockMap } from './clockMap.ts';
import { encodeFrame } from './frame.ts';
import type { Message } from './messages.ts';
import { geometryMessages, timingMessages, type EncodableSegment, type PositionSlot } from './segmentEncoding.ts';

/** Share of a link's bytes that segments may take. */
export const LINK_SHARE = 0.75;
/** Segments per GEOMETRY/TIMING frame assumed: what the streamer batches when segments come fast. */
export const SEGMENTS_PER_FRAME = 4;

/** One device as the limit sees it: how many position tracks it reads, over what link. */
export interface LinkLoad {
  device: string;
  positionSlots: number;
  /** bytes/s to the device; undefined when the link does not say (no limit) */
  bytesPerSecond: number | undefined;
}

export interface FeedLimit {
  /** floor on every segment's duration, µs (0: no link limits the job) */
  minSegment_us: number;
  /** the device whose link sets it, and what it was fed */
  device: string | null;
  bytesPerSegment: number;
  bytesPerSecond: number;
}

/** Bytes one segment costs on the wire to a device reading `positionSlots` position tracks. */
export function bytesPerSegment(positionSlots: number): number {
  if (positionSlots <= 0) return 0;
  const n = SEGMENTS_PER_FRAME;
  const slots: PositionSlot[] = Array.from({ length: positionSlots }, (_, index) => ({ space: 'motion', index }));
  const segments: EncodableSegment[] = Array.from({ length: n }, (_, i) => ({
    length: 1,
    start: slots.map(() => 100 + i),
    end: slots.map(() => 101 + i),
    actuatorStart: [],
    actuatorRate: [],
    // 1 mm from rest to rest at 20 000 mm/s² with a 100 mm/s cruise: three 5 ms phases
    timing: trapezoidTiming(1, 0, 0, 100 * 100, 20_000),
    startTime_us: 1e6 + i * 15_000,
  }));
  const clock = new ClockMap(0, 0, 1);
  const messages: Message[] = [...geometryMessages(segments, slots, 1, false), ...timingMessages(segments, clock, 1, false, 1000, 1e6)];
  let bytes = 0;
  for (const m of messages) bytes += encodeFrame(0, m).length;
  return bytes / n;
}

/** The duration floor that keeps every link within LINK_SHARE of its bytes. */
export function feedLimit(loads: readonly LinkLoad[], share = LINK_SHARE): FeedLimit {
  const limit: FeedLimit = { minSegment_us: 0, device: null, bytesPerSegment: 0, bytesPerSecond: 0 };
  for (const load of loads) {
    if (load.bytesPerSecond === undefined || !(load.bytesPerSecond > 0) || load.positionSlots <= 0) continue;
    const bytes = bytesPerSegment(load.positionSlots);
    const floor_us = (bytes / (load.bytesPerSecond * share)) * 1e6;
    if (floor_us > limit.minSegment_us) {
      limit.minSegment_us = floor_us;
      limit.device = load.device;
      limit.bytesPerSegment = bytes;
      limit.bytesPerSecond = load.bytesPerSecond;
    }
  }
  return limit;
}
