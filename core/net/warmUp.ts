/**
 * A dry run of the streaming path, before real boards get their first segment.
 *
 * Why. The first move after the boards are ready runs code that nothing ran
 * before: the planner, the queue's slicing and locking, the geometry and timing
 * encoders, the frame encoder (COBS, CRC). A JavaScript engine first compiles
 * each function lazily and runs it in its interpreter; only code that ran a few
 * times gets compiled further. So the streamer's first pump that locks a segment
 * does far more work than any pump after it. In the workbench, on a loaded
 * 2-core machine, that pump took 19–111 ms (against 4–6 ms for the pumps after
 * it), and every ms of it is taken out of the start lead of the segment it locks
 * (RTT + startMargin): the board got a TIMING whose start had already passed, and
 * refused it ("TIMING arrived too late"), on a +10 mm jog right after "ready".
 *
 * What. The same Streamer class, on a queue of its own, with the real devices'
 * slots and capacities, streams a short out-and-back move on every motion axis to
 * devices that encode every frame and drop it, on a virtual clock: nothing reaches
 * a board, and the real queue and streamer are untouched. It settles between
 * timers (VirtualScheduler), so it never holds the thread for long.
 */
import type { ResolvedConfig } from '../config/types.ts';
import { VirtualScheduler } from '../time/virtualScheduler.ts';
import { TrajectoryQueue } from '../trajectory/queue.ts';
import { ClockMap } from './clockMap.ts';
import { encodeFrame } from './frame.ts';
import type { Message } from './messages.ts';
import type { PositionSlot } from './segmentEncoding.ts';
import type { SendResult, StreamDevice } from './streamDevice.ts';
import { Streamer, type StreamerOptions } from './streamer.ts';

/** What the dry run needs of each device that reads the trajectory. */
export interface WarmUpDevice {
  name: string;
  positionSlots: PositionSlot[];
  eventSlots: Map<number, number>;
  capacity: number;
}

/** How far the dry move goes along each axis, mm (less where the soft limits are closer). */
const DRY_STEP_MM = 1;
/** The dry run gives up after this much virtual time (µs): a move of a few mm ends long before. */
const DRY_LIMIT_US = 60_000_000;

/** A device that encodes every frame, as a session would, and acknowledges it at once. */
class DryDevice implements StreamDevice {
  readonly isOpen = true;
  readonly rttHigh_us = 0;
  readonly resendAfter_us = 0;
  readonly frameLoss = 0;
  readonly oldestUnacked_us = 0;
  readonly clockMap = new ClockMap(0, 0, 1);
  lastSentSeq = 0;
  /** Bytes encoded: what would have gone out. */
  bytes = 0;

  takeEventRoom(): boolean {
    return true;
  }

  send(message: Message): Promise<SendResult> {
    this.lastSentSeq = (this.lastSentSeq + 1) & 0xff;
    this.bytes += encodeFrame(this.lastSentSeq, message).length;
    return Promise.resolve({ ok: true });
  }
}

/**
 * Where the dry move starts on each axis, and how far it goes: the middle of the
 * soft limits where both are set, else inside the one that is set.
 */
function dryMove(config: ResolvedConfig): { start: number[]; end: number[] } {
  const start: number[] = [];
  const end: number[] = [];
  config.motionAxes.forEach((_, i) => {
    const lo = config.softMin[i];
    const hi = config.softMax[i];
    const finiteLo = Number.isFinite(lo);
    const finiteHi = Number.isFinite(hi);
    const from = finiteLo && finiteHi ? (lo + hi) / 2 : finiteLo ? lo + DRY_STEP_MM : finiteHi ? hi - DRY_STEP_MM : 0;
    const step = finiteLo && finiteHi ? Math.min(DRY_STEP_MM, (hi - lo) / 4) : DRY_STEP_MM;
    start.push(from);
    end.push(finiteHi && !finiteLo ? from - step : from + step);
  });
  return { start, end };
}

/**
 * Streams a short out-and-back move on every axis to dry devices with the given
 * slots, with the real streamer's options, and resolves with the bytes it encoded
 * (0 when no device reads the trajectory). Sends nothing anywhere.
 */
export async function warmStreamingPaths(config: ResolvedConfig, devices: WarmUpDevice[], options: Partial<StreamerOptions> = {}): Promise<number> {
  if (devices.length === 0 || config.motionAxes.length === 0) return 0;
  const scheduler = new VirtualScheduler(0);
  const { start, end } = dryMove(config);
  const queue = new TrajectoryQueue(config, start);
  const dry = devices.map(() => new DryDevice());
  const bindings = devices.map((d, i) => ({ name: d.name, device: dry[i], positionSlots: d.positionSlots, eventSlots: d.eventSlots, capacity: d.capacity }));
  const streamer = new Streamer(queue, scheduler, bindings, () => undefined, options);
  streamer.start();
  try {
    queue.append({ endPosition: end });
    queue.append({ endPosition: start });
    await scheduler.runWhile(() => !streamer.idle, DRY_LIMIT_US);
  } finally {
    streamer.stop();
  }
  return dry.reduce((sum, d) => sum + d.bytes, 0);
}
