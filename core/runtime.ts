/**
 * The distributed side of a MAXL author: sessions with every device, clock sync,
 * subscriptions, streaming, and what an app needs to watch it all.
 *
 *   begin()  opens a session per link (hello, readers), checks the configured
 *            subscriptions against what the devices report (one error listing every
 *            mismatch), subscribes the readers, syncs clocks, and starts streaming.
 *   pause(), resume(), cancel()  stop on the path and hold, go on, or stop and drop
 *            the rest.
 *   halt()   stops every device now (HALT), drops everything queued.
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
import type { Link } from './net/link.ts';
import type { MessageOf } from './net/messages.ts';
import { DeviceState, nameOf, type DeviceStateName } from './net/protocol.ts';
import { DeviceSession, type DeviceInfo, type SessionOptions } from './net/session.ts';
import { Streamer, type StreamerEvent, type StreamerOptions } from './net/streamer.ts';
import { feedLimit, type FeedLimit } from './net/linkFeedLimit.ts';
import { WIRE_MIN_SEGMENT_S } from './trajectory/moves.ts';

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
   * own (an event evaluator; device null), said by the `error` just before: every device
   * comes to rest on the path, with nothing more to run.
   */
  | { type: 'streamStopped'; device: string | null };

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

  constructor(host: RuntimeHost, options: RuntimeOptions) {
    this.host = host;
    this.options = options;
    this.scheduler = options.scheduler;
  }

  /** The floor on segment durations that keeps every link within its bytes (null before begin()). */
  get feedLimit(): Readonly<FeedLimit> | null {
    return this.limit;
  }

  /** Sets the queue's floor on segment durations from the links' bytes/s and the subscriptions. */
  private limitFeedToLinks(plans: readonly DevicePlan[], infos: readonly DeviceInfo[]): void {
    const links = this.options.links;
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

  async begin(): Promise<DeviceInfo[]> {
    const { links, session: sessionOptions } = this.options;
    if (links.length === 0) throw new MaxlError('DEVICE_UNAVAILABLE', 'no links to open: connect a device or choose a simulated machine');
    for (const link of links) {
      const session: DeviceSession = new DeviceSession(
        link,
        this.scheduler,
        {
          status: (s, at) => this.onStatus(session, s, at),
          samples: (m, at) => this.onSamples(session, m, at),
          lost: (reason) => this.onLost(session, reason),
          rebooted: () => this.emit({ type: 'device', device: session.label, state: 'rebooted' }),
        },
        sessionOptions,
      );
      this.sessions.push(session);
    }
    const infos = await Promise.all(this.sessions.map((s) => s.open()));
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
    await this.scheduler.sleep(sync);
    for (const s of this.sessions) this.emit({ type: 'device', device: s.label, state: 'open' });

    const bindings = plans
      .filter((p) => p.readsTrajectory)
      .map((p) => {
        const session = this.sessions[infos.findIndex((i) => i.name === p.device)];
        return { name: p.device, device: session, positionSlots: p.positionSlots, eventSlots: p.eventSlots, capacity: (session.info as DeviceInfo).segmentCapacity };
      });
    this.streamer = new Streamer(this.host.queue, this.scheduler, bindings, (e) => this.onStreamer(e), this.options.streamer);
    this.streamer.start();
    return infos;
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

  whenIdle(): Promise<void> {
    return this.requireStreamer().whenIdle();
  }

  pause(): Promise<void> {
    return this.requireStreamer().pause();
  }

  resume(): void {
    this.requireStreamer().resume();
  }

  cancel(): Promise<void> {
    return this.requireStreamer().cancel();
  }

  /** Stops every device at once, where it is, and drops everything queued. */
  async halt(): Promise<void> {
    this.halted = true;
    this.streamer?.stop();
    // HALT goes out first: nothing the author's queue does may delay or prevent it.
    const halts = Promise.all(this.sessions.filter((s) => s.state === 'open').map((s) => s.send({ type: 'HALT', mode: 0, at: 0 })));
    try {
      this.host.queue.cancelAll();
    } catch (err) {
      // The queue refuses to drop a path it could not brake along; after HALT every
      // device stands still where it is, so that check does not apply. Nothing more streams.
      if (!(err instanceof MaxlError && err.code === 'CANNOT_STOP_IN_PATH')) throw err;
    }
    await halts;
  }

  /** Ends every session. */
  async end(): Promise<void> {
    this.streamer?.stop();
    await Promise.all(this.sessions.map((s) => s.close()));
  }

  private requireStreamer(): Streamer {
    if (!this.streamer) throw new MaxlError('NOT_STARTED', 'call begin() first');
    return this.streamer;
  }

  private onStreamer(e: StreamerEvent): void {
    if (e.type === 'conflict') this.emit({ type: 'error', error: new MaxlError('BUFFER_CONFLICT', e.message) });
    else if (e.type === 'refused') this.onRefused(e);
    else if (e.type === 'failed') this.stopStream(null, e.error);
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
    const what = e.reason === 'LATE_SEGMENT' ? 'arrived too late to run (the link or the author fell behind)' : `was refused (${e.reason}, detail ${e.detail})`;
    if (e.message.type === 'EVENTS') {
      this.emit({ type: 'error', error: new MaxlError('DEVICE_REFUSED', `${e.device}: event changes ${what}; the motion goes on`) });
      return;
    }
    if (this.streamStopped) return;
    this.stopStream(
      e.device,
      new MaxlError('DEVICE_REFUSED', `${e.device}: ${e.message.type} ${what}. Streaming stopped: every device comes to rest on the path. Start the job again from there.`),
    );
  }

  /**
   * Streaming stops for good (once): no device gets more timing, so all run out of
   * it together and brake along the geometry they hold, to rest on the path. One
   * error says why; waits for the job's end (whenIdle) reject with it: it will not end.
   */
  private stopStream(device: string | null, error: MaxlError): void {
    if (this.streamStopped) return;
    this.streamStopped = true;
    this.streamer?.stop(error);
    this.emit({ type: 'error', error });
    this.emit({ type: 'streamStopped', device });
  }
  private streamStopped = false;

  private onStatus(session: DeviceSession, s: MessageOf<'STATUS'>, _at: number): void {
    const state = nameOf(DeviceState, s.state);
    if (state === 'stopped' || state === 'halted') {
      const seg = this.segmentForWireId(s.segmentId);
      const position = seg ? seg.start.map((p, i) => p + seg.unit[i] * seg.length * s.sigma) : null;
      this.emit({ type: 'stopped', device: session.label, segmentId: seg?.id ?? null, sigma: s.sigma, position });
    }
    // After a HALT or a refusal that stopped the stream, braking is what was asked for and was said.
    if (state === 'braking' && !this.halted && !this.streamStopped) {
      this.emit({
        type: 'error',
        error: new MaxlError('LINK_LOST', `${session.label} ran out of timing and is braking along the path: the stream fell behind`),
      });
    }
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
    this.emit({ type: 'device', device: session.label, state: 'lost', reason });
    this.emit({
      type: 'error',
      error: new MaxlError(
        'LINK_LOST',
        `${session.label}: ${reason}. Streaming stopped: every device brakes to rest on the path. Check the cable, then start again.`,
      ),
    });
    // Stop timing everything: every device then brakes along the same geometry.
    this.streamer?.stop();
  }
}
