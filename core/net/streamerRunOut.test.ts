/**
 * When devices run out of timing, the streamer says what held it back
 * (Streamer.runOutReason, which the runtime's LINK_LOST error carries): a device
 * whose ack is overdue, or a pump that came only after the timed path had ended.
 * And a lead that follows how late the pumps have come (lagAllowance_us,
 * core/time/recentWorst.ts), so that a thread held back once is covered the
 * next time, whichever of its timers saw it, and the worst round trip of a while.
 */
import { describe, expect, it } from 'vitest';
import { lightPainter } from '../sim/presets/index.ts';
import { resolveConfig } from '../config/validate.ts';
import { VirtualScheduler } from '../time/virtualScheduler.ts';
import type { Timer } from '../time/scheduler.ts';
import { RecentWorst } from '../time/recentWorst.ts';
import { TrajectoryQueue } from '../trajectory/queue.ts';
import { ClockMap } from './clockMap.ts';
import type { SendResult, StreamDevice } from './streamDevice.ts';
import { Streamer, type StreamerEvent, type StreamerOptions } from './streamer.ts';

/** A device that acknowledges at once, until told to hold its acks. */
class AckingDevice implements StreamDevice {
  readonly isOpen = true;
  rttHigh_us = 1_000;
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

  /** The held acks arrive (their frames stay unanswered here: only the overdue age matters). */
  releaseAcks(): void {
    this.holdAcks = false;
    this.unackedSince = null;
  }

  send(): Promise<SendResult> {
    this.lastSentSeq = (this.lastSentSeq + 1) & 0xff;
    if (!this.holdAcks) return Promise.resolve({ ok: true });
    this.unackedSince ??= this.scheduler.now();
    return new Promise<SendResult>(() => undefined);
  }
}

/**
 * Virtual time whose first timer set for each of `from_us` or later fires late
 * (by `late_us`, or by the matching entry of it): a thread held back once each time.
 */
class HeldBack extends VirtualScheduler {
  private readonly from_us: number[];
  private readonly late_us: number[];
  constructor(from_us: number | number[], late_us: number | number[]) {
    super(0);
    this.from_us = [from_us].flat();
    this.late_us = Array.isArray(late_us) ? [...late_us] : this.from_us.map(() => late_us);
  }

  override at(at_us: number, callback: () => void): Timer {
    if (this.from_us.length === 0 || at_us < this.from_us[0]) return super.at(at_us, callback);
    this.from_us.shift();
    return super.at(at_us + (this.late_us.shift() ?? 0), callback);
  }
}

/** Virtual time that reports hold-backs of its thread as a RealScheduler does (recentLateness_us), here set by hand, remembered 100 ms. */
class ReportsLateness extends VirtualScheduler {
  private readonly late = new RecentWorst(100_000);
  heldBack(late_us: number): void {
    this.late.note(this.now(), late_us);
  }
  recentLateness_us(since_us: number): number {
    return this.late.worst(this.now(), since_us);
  }
}

/** A streamer to `names` (queues of `capacity` segments), and what it reported (its events). */
function streamTo(scheduler: VirtualScheduler, names: string[], options: Partial<StreamerOptions> = {}, capacity = 32) {
  const config = resolveConfig(lightPainter().config);
  const queue = new TrajectoryQueue(config, [10, 10]);
  const devices = names.map(() => new AckingDevice(scheduler));
  const slots = config.motionAxes.map((_, index) => ({ space: 'motion' as const, index }));
  const bindings = names.map((name, i) => ({ name, device: devices[i], positionSlots: slots, eventSlots: new Map<number, number>(), capacity }));
  const events: StreamerEvent[] = [];
  const streamer = new Streamer(queue, scheduler, bindings, (e) => events.push(e), options);
  streamer.start();
  // 20 mm at 50 mm/s: ~0.4 s, sliced a few ms at a time.
  queue.append({ endPosition: [30, 10], maxVelocity: 50 });
  return { streamer, devices, queue, events };
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
    const scheduler = new HeldBack(100_000, 80_000);
    const { streamer } = streamTo(scheduler, ['a']);
    await scheduler.runUntil(99_000);
    expect(streamer.runOutReason()).toBeNull();
    await scheduler.runUntil(200_000);
    // The pump due at 100 ms ran at 180 ms; the lead (2·1 ms + 2.5 ms) had long run out.
    expect(streamer.runOutReason()).toMatch(/^the author's next pump came 8\d\.\d ms after the one before, when only \d+\.\d ms of motion had been sent ahead \(its thread was held back\)$/);
    streamer.stop();
  });

  it('after pumps that an overdue ack held back, names the ack, and the next pump that found the path ended', async () => {
    const scheduler = new VirtualScheduler(0);
    const { streamer, devices } = streamTo(scheduler, ['a', 'b']);
    await scheduler.runUntil(100_000);
    devices[1].holdAcks = true;
    // The timed path (a 4.5 ms lead) ends while nothing can be sent; the pumps stay on time.
    const reasons = new Set<string>();
    for (let t = 100_500; t <= 120_000; t += 500) {
      await scheduler.runUntil(t);
      reasons.add(streamer.runOutReason(1_000) ?? 'none');
    }
    devices[1].releaseAcks();
    await scheduler.runUntil(121_500);
    reasons.add(streamer.runOutReason(1_000) ?? 'none');
    expect([...reasons].filter((r) => r !== 'none' && !/^b had not acknowledged a frame for \d+\.\d ms/.test(r))).toEqual([]);
    // The pump after the last stalled one found the path ended: both are said.
    expect([...reasons].filter((r) => /; the author's next pump came 1\.0 ms after that, when 0\.\d ms of motion were left$/.test(r))).toHaveLength(1);
    expect(streamer.runOutReason()).toMatch(/^b had not acknowledged a frame for \d+\.\d ms/);
    streamer.stop();
  });
});

describe('a lead that follows the pumps’ lateness (lagAllowance_us)', () => {
  // The real boards' margins (app/worker/realBoardStreamer.ts): 13.28 ms, of which 8 ms for the thread's own lateness.
  const REAL: Partial<StreamerOptions> = { leadMargin_us: 13_280, startMargin_us: 13_280, lagAllowance_us: 8_000 };

  it('grows by what a pump came later than the allowance, with the stall limit, and shrinks back a window later', async () => {
    const scheduler = new HeldBack(100_000, 30_000);
    const { streamer } = streamTo(scheduler, ['a'], { ...REAL, lagWindow_us: 200_000 });
    await scheduler.runUntil(99_000);
    // 2·RTT + margin: 2 + 13.28 ms.
    expect(streamer.lead_us).toBe(15_280);
    expect(streamer.startLead_us).toBe(14_280);
    expect(streamer.stallLimit_us).toBe(3_000);
    await scheduler.runUntil(140_000);
    // The pump due at ≥ 100 ms ran 30 ms late: 22 ms beyond the allowance, covered twice (lagCover).
    expect(streamer.lead_us).toBe(15_280 + 44_000);
    expect(streamer.startLead_us).toBe(14_280 + 44_000);
    // And an ack may be late by as much before all timing is held back: RTT + 1 ms + 44 ms.
    expect(streamer.stallLimit_us).toBe(1_000 + 1_000 + 44_000);
    await scheduler.runUntil(400_000);
    expect(streamer.lead_us).toBe(15_280);
    streamer.stop();
  });

  it('covers a hold-back like one it has seen, where a fixed margin runs out again', async () => {
    for (const lagAllowance_us of [8_000, Infinity]) {
      const scheduler = new HeldBack([100_000, 250_000], 30_000);
      const { streamer } = streamTo(scheduler, ['a'], { ...REAL, lagAllowance_us });
      await scheduler.runUntil(200_000);
      // The first hold-back (30 ms against a 15.3 ms lead) ran the device out either way.
      expect(streamer.runOutReason()).toMatch(/^the author's next pump came 3\d\.\d ms after the one before/);
      await scheduler.runUntil(300_000);
      const second = streamer.runOutReason(40_000);
      if (lagAllowance_us === Infinity) expect(second).toMatch(/^the author's next pump came 3\d\.\d ms after the one before/);
      else expect(second).toBeNull();
      streamer.stop();
    }
  });

  it('once held back, covers a longer hold-back with the busy excess (busyExcess_us), where twice the first runs out', async () => {
    // A 14 ms hold-back (6 ms beyond the allowance), then, 150 ms later, one of 60 ms: 4.3 times as long.
    for (const busyExcess_us of [0, 100_000]) {
      const scheduler = new HeldBack([100_000, 250_000], [14_000, 60_000]);
      const { streamer } = streamTo(scheduler, ['a'], { ...REAL, busyExcess_us });
      await scheduler.runUntil(200_000);
      expect(streamer.runOutReason()).toBeNull();
      // lagCover's 2 · 6 ms, or the busy excess.
      expect(streamer.lead_us).toBe(15_280 + Math.max(12_000, busyExcess_us));
      expect(streamer.startLead_us).toBe(14_280 + Math.max(12_000, busyExcess_us));
      await scheduler.runUntil(330_000);
      const second = streamer.runOutReason(80_000);
      if (busyExcess_us === 0) expect(second).toMatch(/^the author's next pump came 6\d\.\d ms after the one before/);
      else expect(second).toBeNull();
      streamer.stop();
    }
  });

  it('sends the busy excess where the devices have room, and calls only a path short of the quiet lead a buffer conflict', async () => {
    // 30 pieces of 0.5 mm at 50 mm/s (10 ms each) to devices of 8 segments: the quiet
    // lead (15.3 ms) and the braking distance fit; the busy lead (115.3 ms) does not.
    const scheduler = new HeldBack(20_000, 14_000);
    const { streamer, queue, events } = streamTo(scheduler, ['a'], { ...REAL, busyExcess_us: 100_000 }, 8);
    for (let i = 1; i <= 30; i++) queue.append({ endPosition: [30 + 0.5 * i, 10], maxVelocity: 50 });
    let worstAhead_us = 0;
    for (let t = 450_000; t <= 1_000_000; t += 1_000) {
      await scheduler.runUntil(t);
      worstAhead_us = Math.max(worstAhead_us, queue.transmittedEnd_us - t);
    }
    expect(streamer.lead_us).toBe(115_280);
    expect(events.filter((e) => e.type === 'conflict')).toEqual([]);
    expect(streamer.runOutReason()).toBeNull();
    // What fits was sent: more than the quiet lead, less than the busy one.
    expect(worstAhead_us).toBeGreaterThan(15_280);
    expect(worstAhead_us).toBeLessThan(115_280);
    streamer.stop();
  });

  it('stays as it was by default (Infinity), whatever the pumps do', async () => {
    const scheduler = new HeldBack(100_000, 30_000);
    const { streamer } = streamTo(scheduler, ['a']);
    await scheduler.runUntil(140_000);
    // 2·1 ms + DEFAULT_STREAMER's 2.5 ms.
    expect(streamer.lead_us).toBe(4_500);
    streamer.stop();
  });

  it("grows by the scheduler's hold-backs that no pump saw, since the streamer began only", async () => {
    const scheduler = new ReportsLateness(0);
    scheduler.heldBack(50_000); // before the streamer: not its own
    await scheduler.runUntil(1_000);
    const { streamer } = streamTo(scheduler, ['a'], { ...REAL, lagWindow_us: 200_000 });
    await scheduler.runUntil(50_000);
    expect(streamer.lead_us).toBe(15_280);
    // A ping's timer (say) came 20 ms late between two pumps that both ran on time.
    scheduler.heldBack(20_000);
    expect(streamer.lead_us).toBe(15_280 + 2 * 12_000);
    expect(streamer.stallLimit_us).toBe(2_000 + 2 * 12_000);
    // Forgotten a window later (the scheduler's window here: 100 ms).
    await scheduler.runUntil(160_000);
    expect(streamer.lead_us).toBe(15_280);
    streamer.stop();
  });

  it('keeps the worst round trip of the window, where the last 64 pings forget it', async () => {
    for (const lagAllowance_us of [8_000, Infinity]) {
      const scheduler = new VirtualScheduler(0);
      const { streamer, devices } = streamTo(scheduler, ['a', 'b'], { ...REAL, lagAllowance_us, lagWindow_us: 200_000 });
      await scheduler.runUntil(50_000);
      devices[1].rttHigh_us = 20_000; // a round trip held up on its way (the browser's IO thread, the OS)
      await scheduler.runUntil(60_000);
      devices[1].rttHigh_us = 1_000; // and the pings' recent worst is small again
      await scheduler.runUntil(100_000);
      if (lagAllowance_us === Infinity) {
        expect(streamer.lead_us).toBe(15_280);
        expect(streamer.startLead_us).toBe(14_280);
      } else {
        // 2·20 ms + 13.28 ms, and one trip of 20 ms + 13.28 ms, for a window after the spike.
        expect(streamer.lead_us).toBe(53_280);
        expect(streamer.startLead_us).toBe(33_280);
        expect(streamer.stallLimit_us).toBe(21_000);
        await scheduler.runUntil(270_000);
        expect(streamer.lead_us).toBe(15_280);
      }
      streamer.stop();
    }
  });
});
