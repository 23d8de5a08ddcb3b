/**
 * The distributed side of a MAXL author: sessions with every device, clock sync,
 * subscriptions, streaming, and what an app needs to watch it all.
 *
 *   begin()  opens a session per link (hello, readers), checks the configured
 *            subscriptions against what the devices report (one error listing every
 *            mismatch), subscribes the readers, syncs clocks, and starts streaming.
 *   pause(), resume(), cancel()  stop on the path and hold, go on, or stop and drop
 *            the rest.
 *   halt()   stops every device now (HALT); the rest of the job stays queued.
 *   reconnect(), resumeJob(), discardJob()  after a stop off the plan (a lost link,
 *            a restarted device, a HALT, a refusal): re-open the links, learn where
 *            each board stopped, re-sync, and run (or drop) the rest of the job
 *            (docs/architecture.md §10).
 *   estimate()  where the machine is now, by the author's clock.
 */
import { MaxlError } from './errors.ts';
import type { Scheduler } from './time/scheduler.ts';
import type { TrajectoryQueue } from './trajectory/queue.ts';
import type { Segment } from './trajectory/segment.ts';
import type { TrajectorySample } from './trajectory/tracks.ts';
import type { ResolvedConfig } from './config/types.ts';
import { bindSubscriptions, type DevicePlan } from './net/bindings.ts';
import { SensorCapture, type SampleGap } from './capture/sensorCapture.ts';
import { checkLinks, type Link } from './net/link.ts';
import type { MessageOf } from './net/messages.ts';
import { DeviceState, nameOf, StatusFlag, type DeviceStateName } from './net/protocol.ts';
import { DeviceSession, type DeviceInfo, type SessionOptions } from './net/session.ts';
import { Streamer, type StreamerEvent, type StreamerOptions } from './net/streamer.ts';
import { feedLimit, type FeedLimit } from './net/linkFeedLimit.ts';
import { warmStreamingPaths } from './net/warmUp.ts';
import { WIRE_MIN_SEGMENT_S } from './trajectory/moves.ts';
import { onPath, pathInOrder, planResume, pointAtTime, pointFromStatus, slotValuesAt, type BoardStop } from './net/recovery.ts';
import { pointPosition } from './trajectory/restart.ts';

export interface RuntimeOptions {
  links: Link[];
  scheduler: Scheduler;
  session?: Partial<SessionOptions>;
  streamer?: Partial<StreamerOptions>;
  /** how long begin() pings before streaming (µs), so the clock models have a rate */
  syncBeforeStart_us?: number;
  /**
   * Keep planned motion within what the links carry (linkFeedLimit.ts; default true).
   * Off, a job that needs more than a link carries starves its device.
   */
  linkFeedLimit?: boolean;
  /** Stream a dry move to nowhere before begin() resolves, so the first real segment runs warm code (net/warmUp.ts; default false). */
  warmUp?: boolean;
}

/** One device as an app sees it. */
export interface DeviceReport {
  name: string;
  label: string;
  firmware: string;
  readers: DeviceInfo['readers'];
  state: 'open' | 'lost' | 'closed' | 'opening';
  /** the device's own state, from its last STATUS */
  deviceState: DeviceStateName | 'unknown';
  rtt_us: number;
  syncError_us: number;
  resends: number;
}

export type RuntimeEvent =
  | { type: 'device'; device: string; state: 'open' | 'lost' | 'rebooted'; reason?: string }
  | { type: 'error'; error: MaxlError }
  | { type: 'stopped'; device: string; segmentId: number | null; sigma: number; position: number[] | null }
  | { type: 'samples'; device: string; samples: MessageOf<'SAMPLES'>; at_us: number }
  /** Batches of a sensor reader lost (with the samples they held), or a duplicate batch dropped. */
  | { type: 'sampleGap'; device: string; reader: string; gap: SampleGap }
  | { type: 'idle' }
  /**
   * Streaming stopped for good after a refusal (by `device`) or a failure of the author's
   * own (an event evaluator, a buffer conflict; device null), said by the `error` just
   * before: every device comes to rest on the path, with nothing more to run. `what` says
   * in a few words what stopped it.
   */
  | { type: 'streamStopped'; device: string | null; what: string }
  /** reconnect() re-opened every link: the job can resume from `resumeFrom` (resumeJob()) or be dropped (discardJob()). */
  | { type: 'reconnected'; report: RecoveryReport };

/** Why the machine stopped off its plan: what recovery starts from. */
export interface StopRecord {
  reason: 'lost' | 'rebooted' | 'refused' | 'halted';
  /** The device that caused it ('' for a HALT). */
  device: string;
  /** Author µs at which the author learned of it. */
  at_us: number;
}

/** What reconnect() found and did. */
export interface RecoveryReport {
  stop: StopRecord;
  /** Where each board that reads the trajectory stopped, and how that is known. */
  boards: Array<{ device: string; position: number[]; source: BoardStop['source'] }>;
  /** Where the job resumes (motion axes, mm); null if nothing of it was left. */
  resumeFrom: number[] | null;
  /** mm between the boards' stops (they rejoin first when > 0.001). */
  spread_mm: number;
  /** Segments queued to run on resumeJob(). */
  remaining: number;
}

export interface RuntimeHost {
  config: ResolvedConfig;
  queue: TrajectoryQueue;
  sample(t_us: number): TrajectorySample;
}

export class Runtime {
  readonly sessions: DeviceSession[] = [];
  /** Sensor captures, by "device/reader". */
  readonly captures = new Map<string, SensorCapture>();
  private readonly host: RuntimeHost;
  private readonly options: RuntimeOptions;
  private readonly scheduler: Scheduler;
  private streamer: Streamer | null = null;
  private plans: DevicePlan[] = [];
  private listeners = new Set<(e: RuntimeEvent) => void>();
  private halted = false;
  private limit: FeedLimit | null = null;
  private links: Link[];
  /** Set when the machine stopped off its plan; cleared by resumeJob() or discardJob(). */
  private stopRecord: StopRecord | null = null;
  /** 'idle' until reconnect() starts, 'reconnecting' during it, 'reconnected' once the job can resume. */
  private recovery: 'idle' | 'reconnecting' | 'reconnected' = 'idle';
  /** Boards that restarted: author µs at which each was last known to run its old session (its last frame's sending). */
  private readonly restarted = new Map<DeviceSession, number>();
  /** The last stop each session reported, so that a repeated STATUS is not reported again. */
  private readonly lastStop = new Map<DeviceSession, string>();
  /** Set by end(); begin() stops at its next step. */
  private ended = false;
  /** Ends begin()'s clock-sync wait early (set while it waits). */
  private wakeSleeper: (() => void) | null = null;

  constructor(host: RuntimeHost, options: RuntimeOptions) {
    this.host = host;
    this.options = options;
    this.scheduler = options.scheduler;
    this.links = options.links;
  }

  /** Why the machine stopped off its plan, until the job resumes or is dropped; null while all is well. */
  get stopped(): Readonly<StopRecord> | null {
    return this.stopRecord;
  }

  /** The floor on segment durations that keeps every link within its bytes (null before begin()). */
  get feedLimit(): Readonly<FeedLimit> | null {
    return this.limit;
  }

  /** Sets the queue's floor on segment durations from the links' bytes/s and the subscriptions. */
  private limitFeedToLinks(plans: readonly DevicePlan[], infos: readonly DeviceInfo[]): void {
    const links = this.links;
    const loads = plans
      .filter((p) => p.readsTrajectory)
      .map((p) => ({ device: p.device, positionSlots: p.positionSlots.length, bytesPerSecond: links[infos.findIndex((i) => i.name === p.device)]?.bytesPerSecond }));
    this.limit = this.options.linkFeedLimit === false ? feedLimit([]) : feedLimit(loads);
    // And never under the wire's own floor: a segment timed 0 µs is one the reader refuses.
    this.host.queue.setMinSegmentDuration(Math.max(this.limit.minSegment_us * 1e-6, WIRE_MIN_SEGMENT_S));
  }

  on(listener: (e: RuntimeEvent) => void): () => void {
    this.listeners.add(listener);
    return () => this.listeners.delete(listener);
  }

  private emit(e: RuntimeEvent): void {
    for (const l of this.listeners) l(e);
  }

  /**
   * Opens the sessions, subscribes, syncs clocks and starts streaming. end() while
   * this runs makes it reject at once with QUEUE_CLOSED, whatever step it was at
   * (a hello, a subscription, the clock sync), with nothing it started left running.
   */
  async begin(): Promise<DeviceInfo[]> {
    if (this.links.length === 0) throw new MaxlError('DEVICE_UNAVAILABLE', 'no links to open: connect a device or choose a simulated machine');
    checkLinks(this.links);
    this.createSessions();
    let infos: DeviceInfo[];
    try {
      infos = await Promise.all(this.sessions.map((s) => s.open()));
      // Throws QUEUE_CLOSED itself once end() cuts its clock sync short.
      await this.subscribeAndSync(infos);
      if (this.options.warmUp) await this.warmUp(infos);
    } catch (err) {
      // end() closed the sessions under it: that, not what the closing broke, is why.
      throw this.ended ? endedWhileConnecting() : err;
    }
    this.throwIfEnded();
    this.streamer = this.createStreamer(infos, new Map());
    this.streamer.start();
    return infos;
  }

  private throwIfEnded(): void {
    if (this.ended) throw endedWhileConnecting();
  }

  /** One session per link, its events wired to this runtime. */
  private createSessions(): void {
    for (const link of this.links) {
      const session: DeviceSession = new DeviceSession(
        link,
        this.scheduler,
        {
          status: (s, at) => this.onStatus(session, s, at),
          samples: (m, at) => this.onSamples(session, m, at),
          lost: (reason) => this.onLost(session, reason),
          rebooted: () => {
            // Its last frame before the restart left it about half a round trip before it came.
            this.restarted.set(session, session.heardBefore_us - (session.rtt_us || 0) / 2);
            this.emit({ type: 'device', device: session.label, state: 'rebooted' });
          },
        },
        this.options.session,
      );
      this.sessions.push(session);
    }
  }

  /**
   * Checks the devices against the subscriptions (one error listing every
   * mismatch), subscribes their readers, and syncs clocks before anything is timed.
   */
  private async subscribeAndSync(infos: DeviceInfo[]): Promise<void> {
    const names = infos.map((i) => i.name);
    const twice = names.filter((n, i) => names.indexOf(n) !== i);
    if (twice.length > 0) throw new MaxlError('SUBSCRIPTION_MISMATCH', `two devices are both named "${twice[0]}": give each board its own name`);

    const { plans, mismatches } = bindSubscriptions(this.host.config, infos);
    if (mismatches.length > 0) {
      throw new MaxlError(
        'SUBSCRIPTION_MISMATCH',
        `the configured subscriptions do not match the devices:\n  ${mismatches.map((m) => m.message).join('\n  ')}`,
      );
    }
    this.plans = plans;
    this.limitFeedToLinks(plans, infos);
    for (const plan of plans) {
      const session = this.sessions[infos.findIndex((i) => i.name === plan.device)];
      for (const sub of plan.subscribe) {
        const r = await session.send(sub);
        if (!r.ok) throw new MaxlError('DEVICE_REFUSED', `${plan.device} refused subscription of reader ${sub.reader}: ${r.reason}`);
      }
    }
    // Let the clock models see enough exchanges for a rate before anything is timed.
    const sync = this.options.syncBeforeStart_us ?? 2_000_000;
    for (const s of this.sessions) s.pingBurst(sync + 1_000_000);
    await this.sleepUnlessEnded(sync);
    this.throwIfEnded();
    for (const s of this.sessions) this.emit({ type: 'device', device: s.label, state: 'open' });
  }

  /** Resolves after `delay_us`, or at once when end() is called (which may also stop the scheduler's timers). */
  private sleepUnlessEnded(delay_us: number): Promise<void> {
    return new Promise((resolve) => {
      const timer = this.scheduler.after(delay_us, () => {
        this.wakeSleeper = null;
        resolve();
      });
      this.wakeSleeper = () => {
        timer.cancel();
        this.wakeSleeper = null;
        resolve();
      };
    });
  }

  /** A dry run of the streaming path with these devices' slots, sending nothing (net/warmUp.ts). */
  private async warmUp(infos: DeviceInfo[]): Promise<void> {
    const devices = this.plans
      .filter((p) => p.readsTrajectory)
      .map((p) => ({ name: p.device, positionSlots: p.positionSlots, eventSlots: p.eventSlots, capacity: (infos.find((i) => i.name === p.device) as DeviceInfo).segmentCapacity }));
    await warmStreamingPaths(this.host.config, devices, this.options.streamer);
  }

  /** A streamer for the devices that read the trajectory; `p0` gives a device's slots where they stand, if not at the path's start. */
  private createStreamer(infos: DeviceInfo[], p0: Map<string, number[]>): Streamer {
    const bindings = this.plans
      .filter((p) => p.readsTrajectory)
      .map((p) => {
        const session = this.sessions[infos.findIndex((i) => i.name === p.device)];
        return { name: p.device, device: session, positionSlots: p.positionSlots, eventSlots: p.eventSlots, capacity: (session.info as DeviceInfo).segmentCapacity, p0: p0.get(p.device) };
      });
    return new Streamer(this.host.queue, this.scheduler, bindings, (e) => this.onStreamer(e), this.options.streamer);
  }

  // --- recovery ---

  /**
   * After the machine stopped off its plan (a link lost, a device restarted, a
   * HALT, a refused segment): re-opens every link (the same ones, or `links`
   * in their place, the old ones then closed), asks each board where it stopped,
   * opens fresh sessions, subscribes and re-syncs clocks, and rebuilds the queue
   * from the stop: the rest of the job, nothing lost and nothing run twice. Nothing
   * moves until resumeJob() (or discardJob()).
   */
  async reconnect(links?: Link[]): Promise<RecoveryReport> {
    const stop = this.stopRecord;
    if (!stop) throw new MaxlError('RECOVERY_ORDER', 'nothing to reconnect: the machine has not stopped off its plan (reconnect() follows a lost link, a restarted device, a HALT or a refused segment)');
    if (this.recovery === 'reconnecting') throw new MaxlError('RECOVERY_ORDER', 'reconnect() is already under way');
    if (this.recovery === 'reconnected') throw new MaxlError('RECOVERY_ORDER', 'already reconnected: call resumeJob() to go on, or discardJob() to drop the rest of the job');
    if (links && links.length === 0) throw new MaxlError('DEVICE_UNAVAILABLE', 'no links to open: connect the devices again');
    if (links) checkLinks(links);
    this.recovery = 'reconnecting';
    const old = this.streamer;
    const oldSessions = this.sessions.splice(0);
    try {
      old?.stop();
      await Promise.all(oldSessions.map((s) => s.close(links !== undefined)));
      if (links) this.links = links;
      this.createSessions();
      const probes = await Promise.all(this.sessions.map((s) => s.probe()));
      const infos = await Promise.all(this.sessions.map((s) => s.open()));
      const path = pathInOrder(old?.sentInOrder ?? [], this.untransmitted());
      const stops: BoardStop[] = [];
      infos.forEach((info, i) => {
        const { status, expectedSeq } = probes[i];
        const said = status && old ? pointFromStatus(status, (id) => old.segmentOnDevice(info.name, id, expectedSeq)) : null;
        const fromStatus = said ? onPath(path, said) : null;
        const lastAlive = [...this.restarted].find(([s]) => s.label === info.name)?.[1];
        const estimate = !fromStatus && lastAlive !== undefined ? pointAtTime(path, lastAlive) : null;
        if (fromStatus) stops.push({ device: info.name, point: fromStatus, source: 'status' });
        else if (estimate) stops.push({ device: info.name, point: estimate, source: 'estimate' });
      });
      await this.subscribeAndSync(infos);
      const reading = new Set(this.plans.filter((p) => p.positionSlots.length > 0).map((p) => p.device));
      const boardStops = stops.filter((b) => reading.has(b.device));
      const plan = planResume(path, boardStops);
      const p0 = new Map<string, number[]>();
      let remaining = this.host.queue.untransmittedCount;
      if (plan) {
        for (const b of boardStops) {
          const slots = this.plans.find((p) => p.device === b.device)?.positionSlots ?? [];
          p0.set(b.device, slotValuesAt(b.point, slots));
        }
        remaining = this.host.queue.restartFrom(plan.from, plan.rerun, plan.rejoinFrom).length;
      }
      this.restarted.clear();
      this.lastStop.clear();
      this.streamer = this.createStreamer(infos, p0);
      this.recovery = 'reconnected';
      const report: RecoveryReport = {
        stop: { ...stop },
        boards: boardStops.map((b) => ({ device: b.device, position: pointPosition(b.point), source: b.source })),
        resumeFrom: plan ? pointPosition(plan.from) : null,
        spread_mm: plan?.spread_mm ?? 0,
        remaining,
      };
      this.emit({ type: 'reconnected', report });
      return report;
    } catch (err) {
      // Leave the links free for another try.
      const failed = this.sessions.splice(0);
      await Promise.all(failed.map((s) => s.close(false)));
      this.streamer = old;
      this.recovery = 'idle';
      throw err;
    }
  }

  /** After reconnect(): streams the rest of the job from where the machine stopped. */
  resumeJob(): void {
    this.requireReconnected('resumeJob()');
    this.clearStop();
    this.requireStreamer().start();
  }

  /** After reconnect(): drops the rest of the job; the machine stays where it stopped, ready for new moves. */
  discardJob(): void {
    this.requireReconnected('discardJob()');
    this.host.queue.cancelAll();
    this.clearStop();
    this.requireStreamer().start();
  }

  private requireReconnected(what: string): void {
    if (!this.stopRecord) throw new MaxlError('RECOVERY_ORDER', `${what}: nothing to recover, the machine has not stopped off its plan`);
    if (this.recovery !== 'reconnected') throw new MaxlError('RECOVERY_ORDER', `${what}: call reconnect() first, so that the devices are back, synced and know where they are`);
  }

  private clearStop(): void {
    this.stopRecord = null;
    this.stopError = null;
    this.recovery = 'idle';
    this.halted = false;
    this.streamStopped = false;
  }

  private untransmitted(): Segment[] {
    const out: Segment[] = [];
    for (let i = 0; i < this.host.queue.untransmittedCount; i++) out.push(this.host.queue.untransmittedAt(i) as Segment);
    return out;
  }

  /** Records the first stop off the plan, stops streaming, and tells whoever waits for idle. */
  private stopOffPlan(reason: StopRecord['reason'], device: string, words: string): void {
    if (!this.stopRecord) this.stopRecord = { reason, device, at_us: this.scheduler.now() };
    this.streamer?.stop(this.stoppedError(words));
  }

  private stoppedError(words?: string): MaxlError {
    const stop = this.stopRecord;
    const what = words ?? (stop ? `${stop.reason === 'halted' ? 'it was halted' : `${stop.device}: ${stop.reason}`}` : 'it stopped');
    return new MaxlError('RECOVERY_ORDER', `the machine stopped off its plan (${what}): call reconnect(), then resumeJob() or discardJob()`);
  }

  /** Devices and their link health. */
  devices(): DeviceReport[] {
    return this.sessions.map((s) => ({
      name: s.info?.name ?? s.label,
      label: s.link.label ?? s.label,
      firmware: s.info?.firmware ?? '',
      readers: s.info?.readers ?? [],
      state: s.state === 'closed' ? 'closed' : s.state,
      deviceState: s.lastStatus ? (nameOf(DeviceState, s.lastStatus.state) ?? 'unknown') : 'unknown',
      rtt_us: s.clock.rtt,
      syncError_us: s.clock.errorEstimate_us,
      resends: s.resends,
    }));
  }

  /** Worst current clock-sync error estimate over the devices (µs). */
  get syncError_us(): number {
    let worst = 0;
    for (const s of this.sessions) if (s.state === 'open') worst = Math.max(worst, s.clock.errorEstimate_us);
    return worst;
  }

  get lead_us(): number {
    return this.streamer?.lead_us ?? NaN;
  }

  /** The streamer's stall limit (µs): how long an unacknowledged frame holds all timing back. */
  get streamerStallLimit_us(): number {
    return this.streamer?.stallLimit_us ?? NaN;
  }

  get startLead_us(): number {
    return this.streamer?.startLead_us ?? NaN;
  }

  /**
   * After a stop off the plan: rejects with the error that stopped the stream (a
   * refusal, a failing evaluator), else RECOVERY_ORDER: the job will not reach its
   * end until reconnect() and resumeJob().
   */
  whenIdle(): Promise<void> {
    if (this.stopRecord) return Promise.reject(this.stopError ?? this.stoppedError());
    return this.requireStreamer().whenIdle();
  }

  /** After a stop off the plan the machine already holds at rest: pause() and cancel() resolve and change nothing (the rest of the job waits for resumeJob() or discardJob()). */
  pause(): Promise<void> {
    if (this.stopRecord) return Promise.resolve();
    return this.requireStreamer().pause();
  }

  resume(): void {
    if (this.stopRecord) throw this.stoppedError();
    this.requireStreamer().resume();
  }

  cancel(): Promise<void> {
    if (this.stopRecord) return Promise.resolve();
    return this.requireStreamer().cancel();
  }

  /** Stops every device at once, where it is, and drops everything queued. */
  /**
   * Stops every device at once, where it is. Nothing more streams; the rest of the
   * job stays queued for reconnect() and resumeJob(), or discardJob().
   */
  async halt(): Promise<void> {
    this.halted = true;
    // HALT goes out first: nothing the author's queue does may delay or prevent it.
    const halts = Promise.all(this.sessions.filter((s) => s.state === 'open').map((s) => s.send({ type: 'HALT', mode: 0, at: 0 })));
    this.stopOffPlan('halted', '', 'it was halted');
    await halts;
  }

  /** Ends every session (and a begin() still connecting: it rejects with QUEUE_CLOSED). */
  async end(): Promise<void> {
    this.ended = true;
    this.wakeSleeper?.();
    this.streamer?.stop(new MaxlError('QUEUE_CLOSED', 'the session ended'));
    await Promise.all(this.sessions.map((s) => s.close()));
  }

  private requireStreamer(): Streamer {
    if (!this.streamer) throw new MaxlError('NOT_STARTED', 'call begin() first');
    return this.streamer;
  }

  private onStreamer(e: StreamerEvent): void {
    if (e.type === 'conflict') this.onConflict(e.error);
    else if (e.type === 'refused') this.onRefused(e);
    else if (e.type === 'failed') this.stopStream(null, e.error, 'an event evaluator failed, and streaming stopped');
    else if (e.type === 'idle') this.emit({ type: 'idle' });
  }

  /**
   * A device refused part of the trajectory. Refused events cost a light or a
   * laser level, and are reported. Refused geometry or timing means the devices no
   * longer hold the same trajectory: streaming stops for all of them, so that they
   * all run out of timing together and come to rest on the path, and the job ends
   * with one error saying why (later refusals of the same stop are not repeated).
   */
  private onRefused(e: Extract<StreamerEvent, { type: 'refused' }>): void {
    if (e.reason === 'CLOCK_JUMP') return this.onClockJump(e.device);
    const what = e.reason === 'LATE_SEGMENT' ? 'arrived too late to run (the link or the author fell behind)' : `was refused (${e.reason}, detail ${e.detail})`;
    if (e.message.type === 'EVENTS') {
      this.emit({ type: 'error', error: new MaxlError('DEVICE_REFUSED', `${e.device}: event changes ${what}; the motion goes on`) });
      return;
    }
    if (this.streamStopped) return;
    this.stopStream(
      e.device,
      new MaxlError('DEVICE_REFUSED', `${e.device}: ${e.message.type} ${what}. Streaming stopped: every device comes to rest on the path. Reconnect, then resume the job from there.`),
      `${e.device} refused a segment, and streaming stopped`,
    );
  }

  /**
   * The streamer met a buffer conflict: it has planned the machine to rest and sends
   * nothing past that point (its waits for the path's end reject with the conflict).
   * The stream has stopped as after a refusal, but the devices brake along the planned
   * path instead of running out of timing, so the streamer is not stopped here.
   */
  private onConflict(error: MaxlError): void {
    this.emit({ type: 'error', error });
    this.emit({ type: 'streamStopped', device: null, what: 'a buffer conflict stopped the stream, and the machine brakes to rest on the path' });
  }

  /**
   * Streaming stops for good (once): no device gets more timing, so all run out of
   * it together and brake along the geometry they hold, to rest on the path. One
   * error says why; waits for the job's end (whenIdle) reject with it: it will not end.
   */
  private stopStream(device: string | null, error: MaxlError, what: string): void {
    if (this.streamStopped) return;
    this.streamStopped = true;
    if (!this.stopRecord) {
      this.stopRecord = { reason: 'refused', device: device ?? '', at_us: this.scheduler.now() };
      this.stopError = error;
    }
    this.streamer?.stop(error);
    this.emit({ type: 'error', error });
    this.emit({ type: 'streamStopped', device, what });
  }
  private streamStopped = false;
  /** The error that stopped the stream (a refusal, a failing evaluator), for whenIdle() until the job resumes. */
  private stopError: MaxlError | null = null;

  /**
   * A board's µs counter leapt or ran backwards while it held timing (STATUS flag
   * clockJump, or its refusal of more TIMING). The board mended its clock and runs
   * out of the timing it holds (docs/protocol.md §6 "Clock jumps"); streaming stops
   * for every board, so all run out of the same timing and brake together on the path.
   */
  private onClockJump(device: string): void {
    if (this.streamStopped) return;
    this.stopStream(
      device,
      new MaxlError(
        'DEVICE_REFUSED',
        `${device}: its clock jumped (micros() leapt or ran backwards mid-job); it takes no more timing. Streaming stopped: every device comes to rest on the path. Reconnect, then resume the job from there.`,
      ),
      `${device}'s clock jumped, and streaming stopped`,
    );
  }

  private onStatus(session: DeviceSession, s: MessageOf<'STATUS'>, _at: number): void {
    if (s.flags & StatusFlag.clockJump) this.onClockJump(session.label);
    const state = nameOf(DeviceState, s.state);
    if (state === 'stopped' || state === 'halted') {
      // A board repeats its STATUS every 100 ms while stopped: say each stop once.
      const key = `${state} ${s.segmentId} ${s.sigma}`;
      if (this.lastStop.get(session) === key) return;
      this.lastStop.set(session, key);
      const seg = this.segmentForWireId(s.segmentId);
      const position = seg ? seg.start.map((p, i) => p + seg.unit[i] * seg.length * s.sigma) : null;
      this.emit({ type: 'stopped', device: session.label, segmentId: seg?.id ?? null, sigma: s.sigma, position });
    } else this.lastStop.delete(session);
    // After a HALT or a refusal that stopped the stream, braking is what was asked for and was said.
    if (state === 'braking' && !this.halted && !this.streamStopped) {
      this.emit({
        type: 'error',
        error: new MaxlError('LINK_LOST', `${session.label} ran out of timing and is braking along the path: the stream fell behind${this.runOutReason()}`),
      });
    }
  }

  /** Why the stream may have fallen behind, as the streamer saw it (": …"), or nothing. */
  private runOutReason(): string {
    const why = this.streamer?.runOutReason();
    return why ? `: ${why}` : '';
  }

  private onSamples(session: DeviceSession, m: MessageOf<'SAMPLES'>, at: number): void {
    const reader = session.info?.readers[m.reader];
    const clock = session.clock.clock;
    if (!reader || !clock) return;
    const key = `${session.label}/${reader.name}`;
    let capture = this.captures.get(key);
    if (!capture) {
      capture = new SensorCapture(session.label, reader.name, reader.channels);
      this.captures.set(key, capture);
    }
    const gap = capture.add(m, clock, at);
    if (gap) this.emit({ type: 'sampleGap', device: session.label, reader: reader.name, gap });
    if (gap?.kind !== 'duplicate') this.emit({ type: 'samples', device: session.label, samples: m, at_us: at });
  }

  private segmentForWireId(wireId: number): Segment | undefined {
    return this.streamer?.segmentForWireId(wireId);
  }

  private onLost(session: DeviceSession, reason: string): void {
    if (!this.sessions.includes(session)) return; // a session reconnect() replaced
    const restarted = this.restarted.has(session);
    // Lost after the job's end: everything was sent, every board had acknowledged all
    // of it, and the last segment's end time has passed, so every board has run the
    // job to its end (a cut in its last moments, found by the silence limit after it).
    const queue = this.host.queue;
    const jobDone = !restarted && this.streamer?.allAnswered === true && queue.untransmittedCount === 0 && queue.transmittedEnd_us <= this.scheduler.now();
    // Stop timing everything: every device then brakes along the same geometry.
    this.stopOffPlan(restarted ? 'rebooted' : 'lost', session.label, `${session.label}: ${reason}`);
    this.emit({ type: 'device', device: session.label, state: 'lost', reason });
    const after = jobDone
      ? 'The job had already run to its end on every board: nothing is left to resume. Check the cable and power, then reconnect.'
      : 'Streaming stopped: every device brakes to rest on the path. Check the cable and power, then reconnect and resume the job.';
    this.emit({ type: 'error', error: new MaxlError('LINK_LOST', `${session.label}: ${reason}. ${after}`) });
  }
}

/** begin()'s (or reconnect()'s) error when end() was called before it finished connecting. */
function endedWhileConnecting(): MaxlError {
  return new MaxlError('QUEUE_CLOSED', 'end() was called while connecting: the devices were closed');
}
