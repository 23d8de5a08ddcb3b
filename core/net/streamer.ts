/**
 * Minimal buffering (the paper's Table 1, docs/design.md, decision 4): streams the
 * queue's segments to every device that reads the trajectory, just in time.
 *
 * Each pump, for all devices in lock-step:
 *  1. Timing. While the transmitted path ends less than `lead` ahead of now, or
 *     fewer than 2 transmitted segments are still to run, lock the next segment
 *     (queue.transmitNext) and send its TIMING and EVENTS. lead = 2·RTT plus a
 *     margin: a segment sent now arrives before the one before it ends (plus, on
 *     a link that loses frames, time for the resends it needs: resendAllowance_us). A segment
 *     reaching far past the horizon is split first (queue.splitFront), so only a
 *     slice of it is locked and the rest stays editable: a hold-to-jog stops within
 *     a lead time, and a slow stream of points keeps moving instead of stopping at
 *     each point. Segments under `wholeSegment_us` with more queued after them (a
 *     job's) are locked whole: each slice costs fresh geometry and timing on the
 *     wire (bench/wire.ts), and a pause still comes within that time.
 *  2. Geometry. Every device also holds provisional geometry (segments without
 *     timing) beyond the timed path, at least the distance needed to brake from
 *     the timed path's exit speed at `stopDecel`. If timing stops coming (a dead
 *     link, a pause), every device brakes along that same geometry from the same
 *     instant at the same rate, so all come to rest at the same point on the path.
 *     It is sent before the timing that needs it.
 *  3. Capacity. Geometry on a device never exceeds its queue. When a segment's
 *     timing plus its braking geometry would not fit (tiny fast segments), that is a
 *     buffer conflict: reported, and the machine is brought to rest (the paper's
 *     "error condition and a systems halt"). The author does not slow such a job by
 *     itself: the user lowers its speed or joins its tiny segments (the message says so).
 *
 * Edits to provisional segments (a cancel, a replace, a split) are followed on the
 * devices with REPLACE_TAIL and fresh geometry.
 */
import { MaxlError } from '../errors.ts';
import type { Scheduler, Timer } from '../time/scheduler.ts';
import type { TrajectoryQueue, QueueEvent } from '../trajectory/queue.ts';
import type { Segment } from '../trajectory/segment.ts';
import { evaluateTiming } from '../plan/phases.ts';
import type { SendResult, StreamDevice } from './streamDevice.ts';
import type { Message, MessageOf } from './messages.ts';
import { geometryMessages, type PositionSlot } from './segmentEncoding.ts';
import { timingForPath } from './timedPath.ts';
import { MAX_PAYLOAD } from './protocol.ts';
import { RecentWorst } from '../time/recentWorst.ts';

/** What one device reads of the trajectory, and how to reach it. */
export interface DeviceBinding {
  name: string;
  device: StreamDevice;
  /** position tracks, in slot order */
  positionSlots: PositionSlot[];
  /** event channel index → event slot */
  eventSlots: Map<number, number>;
  /** queue depth the device reported */
  capacity: number;
  /** Where each position slot stands, for the first GEOMETRY, when not at the path's start (a resumed job). */
  p0?: number[];
}

export interface StreamerOptions {
  /** lead time at least this (µs) */
  minLead_us: number;
  /**
   * added to 2·RTT for the lead time (µs): the author's and the device's own latency,
   * and room for one resend of a frame whose nack was lost
   */
  leadMargin_us: number;
  /** a segment after rest starts this long after RTT from now (µs) */
  startMargin_us: number;
  /** long segments are locked in slices reaching this far past the horizon (µs) */
  slice_us: number;
  /** segments up to this long (µs) with more queued after them are locked whole, not sliced */
  wholeSegment_us: number;
  /** when the timed path falls short of the horizon, it is topped up this far (µs) past it */
  refill_us: number;
  /** pump period while anything moves or waits (µs) */
  tick_us: number;
  /**
   * The part of the margins (µs) meant for the author's own thread coming late (a
   * timer's clamp, a long task). With it finite (real boards), the streamer
   * follows the machine's recent hold-backs (core/time/recentWorst.ts): whatever
   * its pumps, or the scheduler's other timers (Scheduler.recentLateness_us), came
   * later than this within the last `lagWindow_us` is added to the lead, the start
   * lead and the stall limit; and the round trip in them is the worst the links
   * showed over that window, not only their last 64 pings. Infinity (the default):
   * none of this, the margins are fixed.
   */
  lagAllowance_us: number;
  /** how far back (µs) the hold-backs and round trips are remembered */
  lagWindow_us: number;
  /**
   * How many times over the excess hold-back is covered: a machine that has just
   * held the thread back by x will likely do so again, and not always by less (the
   * WebSerial spec's loaded runs: a 70.7 ms lead grown after a hold-back, then a
   * pump 76.6 ms late). 2: the lead covers a hold-back up to twice the worst seen.
   */
  lagCover: number;
  /**
   * The least (µs) the lead, the start lead and the stall limit gain once the window
   * holds any hold-back beyond the allowance: a machine busy enough to hold the
   * author back once holds it back again, and further. In the WebSerial spec's
   * loaded runs (two CPU burners on two cores), each stream that began after a
   * hold-back of 14–33 ms met one of 32–63 ms within the next second, 1.7–3.8
   * times the first, and bytes on their way to the boards were held up to 87 ms:
   * covering twice the worst seen (lagCover) ran the boards out in 3 runs of 40.
   * 0 (the default): only lagCover. The lead's part above the quiet lead is
   * best-effort: where the devices' queues cannot hold that much motion, the
   * streamer sends what fits, and only a path that cannot reach the quiet lead
   * is a buffer conflict.
   */
  busyExcess_us: number;
}

export const DEFAULT_STREAMER: StreamerOptions = {
  minLead_us: 2_000,
  leadMargin_us: 2_500,
  startMargin_us: 700,
  slice_us: 4_000,
  wholeSegment_us: 50_000,
  refill_us: 2_000,
  tick_us: 1_000,
  lagAllowance_us: Infinity,
  lagWindow_us: 10_000_000,
  lagCover: 2,
  busyExcess_us: 0,
};

/** How rarely a frame may miss its lead on a lossy link (resendAllowance_us). */
const LATE_FRAME_ODDS = 1e-3;
/** Resends a lead covers at most (resendAllowance_us): each costs a resend timeout, ≥ 4 ms. */
const MAX_COVERED_RESENDS = 4;

export type StreamerEvent =
  | { type: 'conflict'; error: MaxlError }
  | { type: 'refused'; device: string; reason: string; detail: number; message: Message }
  /** The pump could not go on: an event evaluator threw or returned a non-number while its segment was locked. */
  | { type: 'failed'; error: MaxlError }
  | { type: 'idle' };

interface DeviceState {
  binding: DeviceBinding;
  /** device µs (unwrapped) at which its timed path ends, and the author µs it stands for */
  timedEnd: number | null;
  timedEndAuthor: number;
  /** the next GEOMETRY must say where each slot starts */
  needP0: boolean;
  /** event entries waiting for room on the device */
  pendingEvents: MessageOf<'EVENTS'>[];
  /** The last GEOMETRY messages given to the session, with their sequence numbers and segments (newest last). */
  geometryLog: Array<{ seq: number; firstId: number; segments: Segment[]; result: 'pending' | 'ok' | 'refused' }>;
  /** Frames of the job posted and not answered (an ack or a refusal) yet, or never: lost with the session. */
  unanswered: number;
}

/** No piece of a split is shorter than this, mm. */
const MIN_SPLIT_MM = 0.01;
/**
 * The shortest slice locked of a long segment, mm: a slice reaches a lead and two
 * slice times ahead, unless that is less path than this (below 2 mm/s or so), so a
 * cancel comes within max(those times, this distance) of motion, whatever the speed.
 */
const MIN_SLICE_MM = 2 * MIN_SPLIT_MM;
/** Segments the wire log keeps (segmentForWireId, sentInOrder): far more than a device queue holds. */
const WIRE_LOG = 2048;
/** Segments nearTailRest() looks at after the next one, at most. */
const TAIL_SCAN = 64;

export class Streamer {
  private readonly queue: TrajectoryQueue;
  private readonly scheduler: Scheduler;
  private readonly devices: DeviceState[];
  private readonly options: StreamerOptions;
  private readonly onEvent: (e: StreamerEvent) => void;
  /** Segments whose geometry the devices hold, oldest first: the first `timed` are transmitted. */
  private sent: Segment[] = [];
  private timed = 0;
  private readonly wireIds = new Map<Segment, number>();
  private nextWireId = 1;
  private tickTimer: Timer | null = null;
  private unsubscribe: (() => void) | null = null;
  private running = false;
  /** While set, the streamer sends no timing for this segment or after it. */
  private holdAt: Segment | null = null;
  private idleWaiters: Array<{ resolve: () => void; reject: (reason: Error) => void }> = [];
  /** Why streaming stopped for good, if it did (a refusal): whenIdle() rejects with it. */
  private stopReason: Error | null = null;
  /**
   * Every segment whose geometry went out, in order, by wire id (the last
   * WIRE_LOG of them): a device's STATUS names where it stopped by wire id, and
   * after a stop off the plan, recovery needs that segment and the ones after it
   * even once the author has retired them (core/runtime.ts, reconnect()).
   */
  private readonly wireLog = new Map<number, Segment>();
  private readonly wireOrder: Array<{ seg: Segment; id: number }> = [];
  /** When the last pump ran, and where the timed path ended after it (author µs). */
  private lastPump: { at_us: number; timedEnd_us: number; more: boolean; stalled: boolean } | null = null;
  private readonly pumpLag: RecentWorst;
  /** The worst round trip (rttHigh) of any device at each pump, when the lead follows the machine (lagAllowance_us finite). */
  private readonly recentTrip: RecentWorst;
  /** When this streamer began (author µs): the scheduler's hold-backs before it are not its own. */
  private readonly createdAt_us: number;
  /** The latest reason the devices could run out of timing (runOutReason). */
  private holdBack: { at_us: number; text: string } | null = null;

  constructor(
    queue: TrajectoryQueue,
    scheduler: Scheduler,
    devices: DeviceBinding[],
    onEvent: (e: StreamerEvent) => void,
    options: Partial<StreamerOptions> = {},
  ) {
    this.queue = queue;
    this.scheduler = scheduler;
    this.devices = devices.map((binding) => ({ binding, timedEnd: null, timedEndAuthor: NaN, needP0: true, pendingEvents: [], geometryLog: [], unanswered: 0 }));
    this.onEvent = onEvent;
    this.options = { ...DEFAULT_STREAMER, ...options };
    this.pumpLag = new RecentWorst(this.options.lagWindow_us);
    this.recentTrip = new RecentWorst(this.options.lagWindow_us);
    this.createdAt_us = scheduler.now();
  }

  /**
   * Time (µs) for the resends a frame to `device` may need on its link as measured,
   * added to every lead below.
   *
   * A frame that is lost goes again at the latest resendAfter_us later (a NACK may
   * bring it sooner). With f the share of the link's recent frames found corrupted
   * (frameLoss), a frame covered for k resends is late with probability
   * about f^(k+1), so k is the least with f^(k+1) ≤ LATE_FRAME_ODDS:
   *   k = ⌈ln(LATE_FRAME_ODDS) / ln f⌉ − 1,  at most MAX_COVERED_RESENDS.
   * On a clean link f = 0, k = 0: every lead is as it was (a slow link's late acks
   * resend frames, but corrupt none). Under byte corruption 10⁻² (frames of 20–40
   * bytes fail 18–33 % of the time; accelRig's boards measured f = 0.20 and 0.28)
   * k = 4, the cap: ~4 × 5 ms more lead.
   * (Without it, a start whose first frames were lost came too late: accelRig, seed
   * 95 of the corruption cases, five stops. The round trips of resent pings, which
   * counted the resend's wait, had padded these leads by chance: clockSync.ts, Karn's rule.)
   */
  private resendAllowance_us(device: StreamDevice): number {
    const f = Math.min(device.frameLoss, 0.99);
    if (!(f > 0)) return 0;
    const resends = Math.min(MAX_COVERED_RESENDS, Math.max(0, Math.ceil(Math.log(LATE_FRAME_ODDS) / Math.log(f)) - 1));
    return resends * device.resendAfter_us;
  }

  /** Whether the margins follow the machine's recent hold-backs and round trips (lagAllowance_us finite: real boards). */
  private get followsMachine(): boolean {
    return Number.isFinite(this.options.lagAllowance_us);
  }

  /**
   * The high round trip (µs) to count for `device`: its recent worst (the last 64
   * pings); when the margins follow the machine, at least the worst any device
   * showed over the window (recentTrip), which pings of a second or two forget.
   */
  private trip_us(device: StreamDevice): number {
    return this.followsMachine ? Math.max(device.rttHigh_us, this.recentTrip.worst(this.scheduler.now())) : device.rttHigh_us;
  }

  /** The largest over the devices of a high round trip plus its resend allowance (µs). */
  private get slowestTrip_us(): number {
    let worst = 0;
    for (const d of this.devices) worst = Math.max(worst, this.trip_us(d.binding.device) + this.resendAllowance_us(d.binding.device));
    return worst;
  }

  /**
   * µs added for the recent hold-backs: what the worst lateness of the pumps, or
   * of the scheduler's other timers since this streamer began, over the window,
   * came beyond the margins' allowance (lagAllowance_us), lagCover times over.
   */
  private get lagExcess_us(): number {
    if (!this.followsMachine) return 0;
    const now = this.scheduler.now();
    const late = Math.max(this.pumpLag.worst(now), this.scheduler.recentLateness_us?.(this.createdAt_us) ?? 0);
    const excess = late - this.options.lagAllowance_us;
    return excess > 0 ? Math.max(this.options.lagCover * excess, this.options.busyExcess_us) : 0;
  }

  /** µs of motion kept ahead: 2·RTT (the slowest device's recent worst) plus a margin, plus the resend allowance and the excess hold-backs. */
  get lead_us(): number {
    return this.quietLead_us + this.lagExcess_us;
  }

  /**
   * The lead without the excess hold-backs (µs): what the devices' queues must
   * hold, or the path is a buffer conflict. (The excess is sent where it fits.)
   */
  private get quietLead_us(): number {
    let worst = 0;
    for (const d of this.devices) worst = Math.max(worst, 2 * this.trip_us(d.binding.device) + this.resendAllowance_us(d.binding.device));
    return Math.max(this.options.minLead_us, worst + this.options.leadMargin_us);
  }

  /**
   * A frame unacknowledged for this long (µs) holds all timing back: a high round
   * trip plus 1 ms, plus the resend allowance, plus the excess hold-backs (the
   * author's thread reads the acks: held back, it reads them late).
   */
  get stallLimit_us(): number {
    return Math.max(3_000, this.slowestTrip_us + 1_000 + this.lagExcess_us);
  }

  /** µs from now to the start of a segment after rest: one RTT (the slowest device's worst) plus a margin, plus the resend allowance and the excess hold-backs. */
  get startLead_us(): number {
    return this.slowestTrip_us + this.options.startMargin_us + this.lagExcess_us;
  }

  start(): void {
    this.running = true;
    this.unsubscribe = this.queue.subscribe((e) => this.onQueue(e));
    this.schedulePump(0);
  }

  /**
   * Stops sending anything more; devices finish their timed path and brake along
   * their geometry. Stops streaming for good. With a `reason` (the stream broke off mid-job), every
   * wait for idle rejects with it now and later: the job will not run to its end.
   */
  stop(reason?: Error): void {
    if (reason) this.endPathWith(reason);
    this.running = false;
    this.unsubscribe?.();
    this.unsubscribe = null;
    this.tickTimer?.cancel();
    this.tickTimer = null;
  }

  /** Whether the machine has nothing left to run: no timed segment ahead and nothing to send. */
  get idle(): boolean {
    const now = this.scheduler.now();
    const moving = this.queue.transmittedEnd_us > now;
    const waiting = this.queue.untransmittedCount > 0 && this.holdAt !== this.queue.peekUntransmitted();
    return !moving && !waiting;
  }

  /** Nothing more of the path will run, for `reason`: waits for its end (whenIdle) reject with it, now and from now on. */
  private endPathWith(reason: Error): void {
    if (this.stopReason) return;
    this.stopReason = reason;
    const waiters = this.idleWaiters;
    this.idleWaiters = [];
    for (const w of waiters) w.reject(reason);
  }

  /** Resolves once the machine is idle (or held and at rest). */
  whenIdle(): Promise<void> {
    if (this.stopReason) return Promise.reject(this.stopReason);
    if (this.idle) return Promise.resolve();
    return new Promise((resolve, reject) => this.idleWaiters.push({ resolve, reject }));
  }

  /** Brings the machine to rest on the path as soon as its limits allow, and holds there. */
  async pause(): Promise<void> {
    this.holdAt = this.queue.brakeToRest();
    this.schedulePump(0);
    await this.untilIdleOrStopped();
  }

  /** Continues after a pause. */
  resume(): void {
    this.holdAt = null;
    this.schedulePump(0);
  }

  /** Stops on the path as soon as possible and drops everything after the stopping point. */
  async cancel(): Promise<void> {
    const after = this.queue.brakeToRest();
    if (after) this.queue.cancelFrom(after.id);
    else if (this.queue.transmittedEnd_us <= this.scheduler.now()) this.queue.cancelAll();
    this.holdAt = null;
    this.schedulePump(0);
    await this.untilIdleOrStopped();
  }

  /** Idle, or streaming stopped for good: either way the machine comes to rest and nothing more runs. */
  private untilIdleOrStopped(): Promise<void> {
    return this.whenIdle().catch((err: unknown) => {
      if (err !== this.stopReason) throw err;
    });
  }

  /** The segment a device numbers `wireId`: among those the devices hold, else the last one sent under that id. */
  /** Whether every device answered every frame of the job posted to it (none in flight, none lost with a link). */
  get allAnswered(): boolean {
    return this.devices.every((d) => d.unanswered === 0);
  }

  segmentForWireId(wireId: number): Segment | undefined {
    return this.sent.find((s) => this.wireIds.get(s) === wireId) ?? this.wireLog.get(wireId);
  }

  /**
   * The segment device `name` holds as `wireId`. Ids are reused after a
   * REPLACE_TAIL, so it is the last GEOMETRY naming it that the device handled
   * and did not refuse (one whose answer was lost counts as taken): every frame before `expectedSeq` (its next sequence number, from a probe after
   * the link came back); null trusts every frame sent.
   */
  segmentOnDevice(name: string, wireId: number, expectedSeq: number | null): Segment | undefined {
    const d = this.devices.find((x) => x.binding.name === name);
    if (!d) return this.segmentForWireId(wireId);
    // Frames sent after the last one the device handled: (last − expected + 1) mod 256 of them.
    const last = d.binding.device.lastSentSeq;
    const unhandled = expectedSeq === null ? 0 : (last - expectedSeq + 1) & 0xff;
    for (let i = d.geometryLog.length - 1; i >= 0; i--) {
      const entry = d.geometryLog[i];
      // Not handled yet, or refused (a REPLACE_TAIL too late, its new geometry then out of order): not what it holds.
      if (((last - entry.seq) & 0xff) < unhandled || entry.result === 'refused') continue;
      const k = (wireId - entry.firstId) & 0xffff;
      if (k < entry.segments.length) return entry.segments[k];
    }
    return this.segmentForWireId(wireId);
  }

  /**
   * Why devices that ran out of timing about now may have: the latest time timing
   * was held back, within `within_us` (an ack overdue), or the pump came after the
   * timed path had ended (the author's thread was held back); null if neither.
   */
  runOutReason(within_us = 1_000_000): string | null {
    const h = this.holdBack;
    return h && this.scheduler.now() - h.at_us <= within_us ? h.text : null;
  }

  /** Segments whose geometry went out, in the order sent (the last WIRE_LOG). */
  get sentInOrder(): Segment[] {
    return this.wireOrder.map((w) => w.seg);
  }

  private logWire(seg: Segment, wireId: number): void {
    this.wireLog.set(wireId, seg);
    this.wireOrder.push({ seg, id: wireId });
    if (this.wireOrder.length > WIRE_LOG * 2) {
      for (const old of this.wireOrder.splice(0, this.wireOrder.length - WIRE_LOG)) {
        if (this.wireLog.get(old.id) === old.seg) this.wireLog.delete(old.id);
      }
    }
  }

  // --- the pump ---

  private schedulePump(delay_us: number): void {
    if (!this.running) return;
    const at = this.scheduler.now() + delay_us;
    if (this.tickTimer) this.tickTimer.cancel();
    this.tickTimer = this.scheduler.at(at, () => {
      this.tickTimer = null;
      this.pumpLag.noteLateness(at, this.scheduler.now());
      this.pump();
    });
  }

  /**
   * One pump, run from a timer: nothing it throws may escape into the scheduler (in
   * the workbench, that would end the worker). A failure (an event evaluator that
   * throws or returns a non-number, whose segment then stays queued, unlocked)
   * stops the pump and is reported; the runtime then stops the stream for good, and
   * every device brakes along the geometry it holds and rests on the path.
   */
  private pump(): void {
    try {
      this.pumpOnce();
    } catch (err) {
      const error = err instanceof MaxlError ? err : new MaxlError('STREAM_FAILED', `streaming failed: ${err instanceof Error ? err.message : String(err)}`);
      this.tickTimer?.cancel();
      this.tickTimer = null;
      this.onEvent({ type: 'failed', error });
    }
  }

  private pumpOnce(): void {
    if (!this.running) return;
    const now = this.scheduler.now();
    if (this.followsMachine) {
      let trip = 0;
      for (const d of this.devices) trip = Math.max(trip, d.binding.device.rttHigh_us);
      this.recentTrip.note(now, trip);
    }
    // Executed segments leave the devices' queues and the author's live queue.
    while (this.timed > 0 && this.sent[0].endTime_us <= now) {
      this.wireIds.delete(this.sent[0]);
      this.sent.shift();
      this.timed--;
    }
    this.queue.retireUntil(now);

    const newlyTimed: Segment[] = [];
    const horizon = now + this.lead_us;
    // Once the timed path falls short of the horizon, top it up a little past it, so
    // that a stream of short segments goes out a few per frame, not one per tick:
    // each frame costs ~14 bytes of headers (bench/wire.ts).
    const refill = this.queue.transmittedEnd_us < horizon ? this.options.refill_us : 0;
    // Every device must hold the same timing, or their braking would start from
    // different points. While one has not acknowledged a frame for longer than a
    // round trip should take, nobody gets more timing: if it is gone, all run out
    // together and brake along the same path; if it recovers, streaming goes on.
    // (Frames already in flight when one cable goes can still reach the others: no
    // protocol can make separate links agree on those. The boards then stop apart by
    // at most the motion of this stall limit; docs/protocol.md §6.)
    const stalled = this.devices.some((d) => !d.binding.device.isOpen || d.binding.device.oldestUnacked_us > this.stallLimit_us);
    this.noteHoldBack(now, stalled);
    for (;;) {
      if (stalled) break;
      const next = this.queue.timeFront();
      if (!next || next === this.holdAt) break;
      const ahead = this.countAhead(now);
      if (this.queue.transmittedEnd_us >= horizon + refill && ahead >= 2) break;
      // A start after rest counts from the clock as it reads now, not at the pump's
      // start: the planning above (timeFront, a split) is not taken out of its lead.
      const earliestStart = this.scheduler.now() + this.startLead_us;
      const start = this.queue.nextStart_us(earliestStart);
      // Lock long segments a slice at a time. When the two-segment minimum asks for a
      // segment that starts at or past the horizon and is longer than a lead (a held
      // jog), lock one slice of it, not all of it; shorter ones are locked whole.
      // A segment with more queued after it is locked whole up to `wholeSegment_us`:
      // slicing it would only cost bytes (each slice is fresh geometry and timing),
      // and a pause still comes within that time. The last queued segment (a live
      // stream's, which the next point may extend) is always sliced, and so is one
      // whose plan brakes for the queue's end (nearTailRest): locked whole, its
      // braking would be fixed a whole segment early, and a live stream's next point
      // could no longer lift it.
      const slice = this.options.slice_us;
      const duration_us = next.duration_s * 1e6;
      const last = this.queue.untransmittedCount === 1 || this.nearTailRest(next);
      const beyond = duration_us > this.lead_us + 2 * slice ? slice : 0;
      const reach = horizon + slice - start > 0 ? horizon + slice - start : beyond;
      if (reach > 0 && duration_us > reach + slice && (last || duration_us > this.options.wholeSegment_us)) {
        // At a few mm/s a lead's worth of path is shorter than the smallest piece worth
        // a split (MIN_SLICE_MM): slice that much instead, rather than lock the whole
        // segment (a released jog key at 2 mm/s once ran on to the soft limit).
        const d = Math.max(evaluateTiming(next.timing!, reach * 1e-6, { s: 0, v: 0, a: 0 }).s, MIN_SLICE_MM);
        if (d < next.length - MIN_SPLIT_MM) {
          this.queue.splitFront(d);
          continue;
        }
      }
      if (!this.fits(next)) {
        // Only the refill, or the busy machine's extra lead, lacks room: send what fits.
        if (this.queue.transmittedEnd_us >= now + this.quietLead_us && ahead >= 2) break;
        this.conflict(next);
        break;
      }
      const seg = this.queue.transmitNext(earliestStart) as Segment;
      // `sent` is the timed segments, then the first untransmitted ones: keep it so.
      if (this.sent.length === this.timed) this.sent.push(seg);
      this.timed++;
      newlyTimed.push(seg);
    }
    this.extendGeometry();
    this.send(newlyTimed);
    const more = this.queue.untransmittedCount > 0 && this.holdAt !== this.queue.peekUntransmitted();
    this.lastPump = { at_us: now, timedEnd_us: this.queue.transmittedEnd_us, more, stalled };

    if (this.idle) {
      const waiters = this.idleWaiters;
      this.idleWaiters = [];
      for (const w of waiters) w.resolve();
      this.onEvent({ type: 'idle' });
    }
    // Keep pumping while anything runs or waits; queue events wake it otherwise.
    if (this.queue.transmittedEnd_us > now || (this.queue.untransmittedCount > 0 && this.holdAt !== this.queue.peekUntransmitted())) {
      this.schedulePump(this.options.tick_us);
    }
  }

  /**
   * Notes what holds timing back, for runOutReason(): a device whose frame waits
   * for its ack past the stall limit, or a pump that came only after the timed path
   * the one before left had ended, while more was queued to send (the devices had
   * run out before the author could send it). A late pump is the reason even if it
   * also finds acks overdue: they may be waiting, unread, in its own thread's queue.
   * After a pump that an overdue ack held back, both are said: the timed path ran
   * down while nothing could be sent, then ended before the next pump.
   */
  private noteHoldBack(now: number, stalled: boolean): void {
    const last = this.lastPump;
    if (last && last.more && last.timedEnd_us > last.at_us && now > last.timedEnd_us) {
      const gap_ms = ((now - last.at_us) / 1000).toFixed(1);
      const ahead_ms = ((last.timedEnd_us - last.at_us) / 1000).toFixed(1);
      const text =
        last.stalled && this.holdBack
          ? `${this.holdBack.text}; the author's next pump came ${gap_ms} ms after that, when ${ahead_ms} ms of motion were left`
          : `the author's next pump came ${gap_ms} ms after the one before, when only ${ahead_ms} ms of motion had been sent ahead (its thread was held back)`;
      this.holdBack = { at_us: now, text };
      return;
    }
    if (!stalled) return;
    const held = this.devices.filter((d) => d.binding.device.isOpen).sort((a, b) => b.binding.device.oldestUnacked_us - a.binding.device.oldestUnacked_us)[0];
    const closed = this.devices.find((d) => !d.binding.device.isOpen);
    const text = closed
      ? `${closed.binding.name}'s link was not open, so no device got more timing`
      : `${held.binding.name} had not acknowledged a frame for ${(held.binding.device.oldestUnacked_us / 1000).toFixed(1)} ms (more than the ${(this.stallLimit_us / 1000).toFixed(1)} ms a round trip should take), so no device got more timing`;
    this.holdBack = { at_us: now, text };
  }

  /**
   * Whether `next`'s plan may be braking for the rest at the queue's end: the path
   * queued after it is shorter than the distance needed to brake from its cruise
   * speed, v²/(2a). Then the segment is sliced like the last one, so that a point
   * appended meanwhile (a live stroke's) replans the braking away instead of
   * meeting it a segment later. A dwell after it is a rest no new point can lift,
   * and a queue with more than TAIL_SCAN segments after it is a job's, not a live
   * stream's: neither counts (and the scan stays short).
   */
  private nearTailRest(next: Segment): boolean {
    const brake = next.cruise2 / (2 * next.accel);
    if (!(brake > 0)) return false;
    let after = 0;
    for (let i = 1; i <= TAIL_SCAN; i++) {
      const seg = this.queue.untransmittedAt(i);
      if (!seg) return true;
      if (seg.source.dwell_s !== null) return false;
      after += seg.length;
      if (after >= brake) return false;
    }
    return false;
  }

  /** Transmitted segments that have not ended yet. */
  private countAhead(now: number): number {
    let n = 0;
    for (let i = this.timed - 1; i >= 0 && this.sent[i].endTime_us > now; i--) n++;
    return n;
  }

  /**
   * The deceleration (mm/s²) devices brake at along the provisional segments: their
   * weakest limit. A dwell has no direction, so no limit of its own: it is skipped
   * (braking passes through its point, docs/protocol.md §6).
   */
  private stopDecel(): number {
    let a = Infinity;
    for (let i = this.timed; i < this.sent.length; i++) if (!this.sent[i].isDwell) a = Math.min(a, this.sent[i].accel);
    for (let i = 0; a === Infinity && i < 4; i++) {
      const s = this.queue.untransmittedAt(i);
      if (s && !s.isDwell) a = Math.min(a, s.accel);
    }
    for (let i = this.timed - 1; a === Infinity && i >= 0; i--) if (!this.sent[i].isDwell) a = this.sent[i].accel;
    return a === Infinity ? 1 : a;
  }

  /**
   * Whether the devices can hold `next` with its timing and the geometry to brake
   * from its exit speed, all within their queues.
   */
  private fits(next: Segment): boolean {
    const a = Math.min(this.stopDecel(), next.accel);
    let need = next.exit2 / (2 * a);
    let count = this.timed + 1; // what will be timed, including `next`
    for (let i = 1; need > 0; i++) {
      const s = this.queue.untransmittedAt(i);
      if (!s) break;
      need -= s.length;
      count++;
    }
    const ended = this.sent.length > 0 ? this.sent.filter((s, i) => i < this.timed && s.endTime_us <= this.scheduler.now()).length : 0;
    return this.devices.every((d) => count - ended <= d.binding.capacity);
  }

  /** Sends geometry up to the braking distance past the timed path (and for every timed segment). */
  private extendGeometry(): void {
    const v2 = this.queue.transmittedExit2;
    const a = this.stopDecel();
    let provisional = 0;
    for (let i = this.timed; i < this.sent.length; i++) provisional += this.sent[i].length;
    const want = v2 / (2 * a);
    let i = this.sent.length - this.timed; // index among untransmitted
    while (provisional < want || this.sent.length === this.timed) {
      const s = this.queue.untransmittedAt(i);
      if (!s || this.sent.length >= Math.min(...this.devices.map((d) => d.binding.capacity))) break;
      this.sent.push(s);
      provisional += s.length;
      i++;
      if (provisional >= want) break;
    }
  }

  /** Writes the new geometry, timing and events to every device, in that order. */
  private send(newlyTimed: Segment[]): void {
    const fresh = this.sent.filter((s) => !this.wireIds.has(s));
    const firstId = this.nextWireId;
    for (const s of fresh) {
      this.wireIds.set(s, this.nextWireId);
      this.logWire(s, this.nextWireId);
      this.nextWireId = (this.nextWireId + 1) & 0xffff;
    }
    for (const d of this.devices) {
      if (!d.binding.device.isOpen) continue;
      const messages: Message[] = [];
      if (fresh.length > 0) {
        messages.push(...geometryMessages(fresh, d.binding.positionSlots, firstId, d.needP0, d.needP0 ? d.binding.p0 : undefined));
        d.needP0 = false;
      }
      if (newlyTimed.length > 0) messages.push(...this.timingFor(d, newlyTimed));
      for (const m of messages) {
        if (m.type !== 'GEOMETRY') {
          this.post(d, m);
          continue;
        }
        const from = (m.firstId - firstId) & 0xffff;
        const entry = { seq: 0, firstId: m.firstId, segments: fresh.slice(from, from + m.count), result: 'pending' as 'pending' | 'ok' | 'refused' };
        this.post(d, m, (r) => {
          if (r.ok) entry.result = 'ok';
          else if (!r.unsent) entry.result = 'refused';
        });
        entry.seq = d.binding.device.lastSentSeq;
        d.geometryLog.push(entry);
        if (d.geometryLog.length > WIRE_LOG) d.geometryLog.splice(0, d.geometryLog.length - WIRE_LOG / 2);
      }
      this.flushEvents(d);
    }
  }

  private timingFor(d: DeviceState, segs: Segment[]): Message[] {
    const clock = d.binding.device.clockMap;
    if (!clock) return [];
    const { messages, deviceLengths } = timingForPath(d, segs, clock, (seg) => this.wireIds.get(seg) as number, this.stopDecel());
    segs.forEach((seg, k) => this.queueEvents(d, seg, deviceLengths[k]));
    return messages;
  }

  /**
   * EVENTS for a timed segment: each change at the same fraction of the segment's
   * span on the device's timeline (`deviceLength` µs) as in the author's plan, so
   * offsets never pass the segment's end however its timing was rounded or stretched.
   */
  private queueEvents(d: DeviceState, seg: Segment, deviceLength: number): void {
    if (d.binding.eventSlots.size === 0) return;
    // device µs per author s within this segment; an instant (a 0-s dwell) has all its events at offset 0
    const scale = seg.duration_s > 0 ? deviceLength / seg.duration_s : 0;
    for (const track of this.queue.eventTracksOf(seg)) {
      const slot = d.binding.eventSlots.get(track.channel);
      if (slot === undefined) continue;
      const entries = track.times.map((t, k) => ({
        offset: Math.min(deviceLength, Math.max(0, Math.round(t * scale))),
        value: track.values[k],
      }));
      // As many entries per frame as fit: header 7 bytes, each ≤ 5 + 4.
      const perFrame = Math.floor((MAX_PAYLOAD - 7) / 9);
      for (let i = 0; i < entries.length; i += perFrame) {
        const chunk = entries.slice(i, i + perFrame);
        d.pendingEvents.push({ type: 'EVENTS', segmentId: this.wireIds.get(seg) as number, slot, firstIndex: i, count: chunk.length, entries: chunk });
      }
    }
  }

  private flushEvents(d: DeviceState): void {
    while (d.pendingEvents.length > 0 && d.binding.device.takeEventRoom(d.pendingEvents[0].count)) {
      this.post(d, d.pendingEvents.shift() as MessageOf<'EVENTS'>);
    }
  }

  private post(d: DeviceState, m: Message, onResult?: (r: SendResult) => void): void {
    d.unanswered++;
    d.binding.device.send(m).then(
      (r: SendResult) => {
        if (r.ok || !r.unsent) d.unanswered--;
        onResult?.(r);
        // A frame the session gave up on as it ended was not refused: the runtime hears of the end itself.
        if (!r.ok && !r.unsent) this.onEvent({ type: 'refused', device: d.binding.name, reason: r.reason, detail: r.detail, message: m });
        if (d.pendingEvents.length > 0) this.flushEvents(d);
      },
      () => {
        // The session ended; the runtime hears of it from the session itself.
      },
    );
  }

  private onQueue(e: QueueEvent): void {
    if (e.type === 'removed') {
      // Provisional geometry the devices hold may have been edited away.
      const first = this.sent.findIndex((s, i) => i >= this.timed && e.segments.includes(s));
      if (first >= 0) {
        const fromId = this.wireIds.get(this.sent[first]) as number;
        for (const s of this.sent.slice(first)) this.wireIds.delete(s);
        this.sent.length = first;
        this.nextWireId = fromId;
        for (const d of this.devices) if (d.binding.device.isOpen) this.post(d, { type: 'REPLACE_TAIL', fromId });
      }
    }
    if (e.type === 'added' || e.type === 'removed') this.schedulePump(0);
  }

  private conflict(next: Segment): void {
    const capacity = Math.min(...this.devices.map((d) => d.binding.capacity));
    const error = new MaxlError(
      'BUFFER_CONFLICT',
      `buffer conflict: segment ${next.id} (${next.length.toFixed(3)} mm at up to ${Math.sqrt(next.cruise2).toFixed(1)} mm/s) ` +
        `needs more segments ahead than a device's queue of ${capacity} holds, to stay on time and still be able to brake. ` +
        `The machine is brought to rest. Use longer segments or a lower speed.`,
    );
    this.onEvent({ type: 'conflict', error });
    this.holdAt = this.queue.brakeToRest() ?? this.holdAt;
    // The pump goes on only to send the planned brake: the rest of the path will not run, so a
    // wait for its end rejects with the conflict (it once resolved at rest, as if the job were done).
    this.endPathWith(error);
  }
}
