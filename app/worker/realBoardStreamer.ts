/**
 * Streaming margins for real boards, which run on the wall clock (RealScheduler).
 *
 * The streamer keeps `lead = 2·RTT + leadMargin` of motion sent ahead, and starts
 * a segment after rest `RTT + startMargin` from now (core/net/streamer.ts; RTT is
 * the slowest device's recent worst round trip, measured with PINGs, so it already
 * holds the USB frames, the driver, the OS and the worker's message queue as they
 * are now). The margin covers what a PING does not measure:
 *
 *   burst   the link's time to carry what one pump hands it at once, a GEOMETRY
 *           and a TIMING frame of at most MAX_ENCODED + 1 bytes each (132 bytes;
 *           a PING is a few bytes). Behind an Uno's 250 000 baud UART, 25 kB/s,
 *           that is 132 / 25 000 s = 5.28 ms; on native USB ~0.1 ms.
 *   timer   a worker's setTimeout, nested as the streamer's pump is, fires up to
 *           4 ms late (the HTML spec's clamp after five nested timers).
 *   task    the worker's longest task between two pumps: a frame's snapshot and
 *           a slice of job planning, each well under 1 ms on a quiet machine, and
 *           the OS handing the CPU back to the worker's thread (a scheduler slice
 *           of ~1.5 ms on 2 cores beside equal-priority work): 4 ms.
 *
 *   leadMargin = startMargin = burst + timer + task = 5.28 + 4 + 4 = 13.28 ms
 *
 * The timer and task terms are the author's thread coming late, on a quiet
 * machine. A busy one holds that thread back for tens of ms now and then, more
 * than a PING that happened not to wait behind it shows. So the streamer also
 * measures how late its pumps and the worker clock's other timers come, and
 * whatever they came later than timer + task (8 ms) in the last 10 s is added,
 * twice over (the next hold-back may be longer), to the lead and the start lead;
 * and the round trip it counts is the worst of those 10 s (`lagAllowance_us`,
 * `lagCover`, core/time/recentWorst.ts): 13.28 ms stays the margin where the
 * machine keeps to it, and a loaded machine gets the lead its hold-backs need.
 * Once one hold-back is seen, the lead gains at least BUSY_EXCESS_US, 100 ms:
 * on a loaded machine (the WebSerial spec beside two CPU burners) the next
 * hold-back came within a second and 1.7–3.8 times as long as the first, and
 * the worst held the bytes 87 ms on their way to the boards: twice the first
 * did not cover it (`busyExcess_us`).
 *
 * At USB round trips (1.5–3 ms for a USB full-speed CDC board; ~3 ms for the
 * USB bridge of an Uno) the lead is 2·3 + 13.28 = 19.3 ms ≤ 20 ms. Before the
 * ports moved into the worker, every byte crossed the page's main thread, whose
 * long tasks (a software-rendered WebGL frame, a layout, a screenshot) held the
 * stream back for tens of ms: that took 80 ms. A browser whose workers cannot
 * reach the ports still bridges them through the page (workerSerial.ts), and its
 * boards keep those 80 ms (BRIDGED_STREAMER).
 *
 * The cost of a margin: a hold-to-jog release brakes about a lead later, and a
 * STOP reaches the boards within one RTT whatever the lead.
 */
import type { StreamerOptions } from '../../core/net/streamer.ts';
import { MAX_ENCODED } from '../../core/net/protocol.ts';

/** What one pump hands a link at once: a GEOMETRY and a TIMING frame, each with its 0x00 delimiter. */
export const LINK_BURST_BYTES = 2 * (MAX_ENCODED + 1);
/** A nested setTimeout's clamp, µs. */
export const TIMER_CLAMP_US = 4_000;
/** The worker's longest task between pumps, and the OS's slice, µs. */
export const WORKER_TASK_US = 4_000;

/** The least a lead gains, µs, once the machine has held the worker back beyond its allowance (the header). */
export const BUSY_EXCESS_US = 100_000;

/** Margins for ports bridged through the page (workers without Web Serial/WebUSB). */
export const BRIDGED_STREAMER: Partial<StreamerOptions> = { minLead_us: 80_000, leadMargin_us: 80_000, startMargin_us: 80_000, lagAllowance_us: 80_000 };

export interface RealLink {
  /** bytes/s the link carries to the board; undefined when unknown */
  bytesPerSecond: number | undefined;
  /** whether its bytes cross the page (the bridge) */
  bridged: boolean;
}

/** µs a link takes to carry one pump's burst. */
export function burst_us(bytesPerSecond: number | undefined): number {
  return bytesPerSecond && bytesPerSecond > 0 ? (LINK_BURST_BYTES / bytesPerSecond) * 1e6 : 0;
}

/** The streamer's margins for these boards: the slowest link decides; one bridged port brings the bridge's. */
export function realBoardStreamer(links: readonly RealLink[]): Partial<StreamerOptions> {
  if (links.some((l) => l.bridged)) return BRIDGED_STREAMER;
  const burst = Math.max(0, ...links.map((l) => burst_us(l.bytesPerSecond)));
  const margin = Math.round(burst + TIMER_CLAMP_US + WORKER_TASK_US);
  return { leadMargin_us: margin, startMargin_us: margin, lagAllowance_us: TIMER_CLAMP_US + WORKER_TASK_US, busyExcess_us: BUSY_EXCESS_US };
}
