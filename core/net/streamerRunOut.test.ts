/**
 * When devices run out of timing, the streamer says what held it back
 * (Streamer.runOutReason, which the runtime's LINK_LOST error carries): a device
 * whose ack is overdue, or a pump that came only after the timed path had ended.
 */
import { describe, expect, it } from 'vitest';
import { lightPainter } from '../sim/presets/index.ts';
import { resolveConfig } from '../config/validate.ts';
import { VirtualScheduler } from '../time/virtualScheduler.ts';
import type { Timer } from '../time/scheduler.ts';
import { TrajectoryQueue } from '../trajectory/queue.ts';
import { ClockMap } from './clockMap.ts';
import type { SendResult, StreamDevice } from './streamDevice.ts';
import { Streamer } from './streamer.ts';

/** A device that acknowledges at once, until told to hold its acks. */
class AckingDevice implements StreamDevice {
  readonly isOpen = true;
  readonly rttHigh_us = 1_000;
  readonly resendAfter_us = 4_000;
  readonly frameLoss = 0;
  readonly clockMap = new ClockMap(0, 0, 1);
  lastSentSeq = 0;
  holdAcks = false;
  private unackedSince: number | null = null;
  constructor(private readonly scheduler: VirtualScheduler) {}

  get oldestUnacked_us(): number {
    return this.unackedSince === null ? 0 : this.scheduler.now() - this.unackedSince;
  }

  takeEventRoom(): boolean {
    return true;
  }

  send(): Promise<SendResult> {
    this.lastSentSeq = (this.lastSentSeq + 1) & 0xff;
    if (!this.holdAcks) return Promise.resolve({ ok: true });
    this.unackedSince ??= this.scheduler.now();
    return new Promise<SendResult>(() => undefined);
  }
}

/** Virtual time whose first timer set for `from_us` or later fires `late_us` late: a thread held back once. */
class HeldBackOnce extends VirtualScheduler {
  constructor(
    private from_us: number,
    private readonly late_us: number,
  ) {
    super(0);
  }

  override at(at_us: number, callback: () => void): Timer {
    if (at_us < this.from_us) return super.at(at_us, callback);
    this.from_us = Infinity;
    return super.at(at_us + this.late_us, callback);
  }
}

function streamTo(scheduler: VirtualScheduler, names: string[]) {
  const config = resolveConfig(lightPainter().config);
  const queue = new TrajectoryQueue(config, [10, 10]);
  const devices = names.map(() => new AckingDevice(scheduler));
  const slots = config.motionAxes.map((_, index) => ({ space: 'motion' as const, index }));
  const bindings = names.map((name, i) => ({ name, device: devices[i], positionSlots: slots, eventSlots: new Map<number, number>(), capacity: 32 }));
  const streamer = new Streamer(queue, scheduler, bindings, () => undefined);
  streamer.start();
  // 20 mm at 50 mm/s: ~0.4 s, sliced a few ms at a time.
  queue.append({ endPosition: [30, 10], maxVelocity: 50 });
  return { streamer, devices };
}

describe('why devices ran out of timing (Streamer.runOutReason)', () => {
  it('names the device whose ack is overdue, and how long it has waited', async () => {
    const scheduler = new VirtualScheduler(0);
    const { streamer, devices } = streamTo(scheduler, ['a', 'b']);
    await scheduler.runUntil(100_000);
    expect(streamer.runOutReason()).toBeNull();
    devices[1].holdAcks = true;
    await scheduler.runUntil(150_000);
    expect(streamer.runOutReason()).toMatch(/^b had not acknowledged a frame for \d+\.\d ms \(more than the 3\.0 ms a round trip should take\), so no device got more timing$/);
    streamer.stop();
  });

  it("says that the author's pump came after the timed path had ended, and by how much", async () => {
    const scheduler = new HeldBackOnce(100_000, 80_000);
    const { streamer } = streamTo(scheduler, ['a']);
    await scheduler.runUntil(99_000);
    expect(streamer.runOutReason()).toBeNull();
    await scheduler.runUntil(200_000);
    // The pump due at 100 ms ran at 180 ms; the lead (2·1 ms + 2.5 ms) had long run out.
    expect(streamer.runOutReason()).toMatch(/^the author's next pump came 8\d\.\d ms after the one before, when only \d+\.\d ms of motion had been sent ahead \(its thread was held back\)$/);
    streamer.stop();
  });
});
