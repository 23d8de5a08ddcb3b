/**
 * createMAXL: the author object of the paper (Listings 1, 2 and 5). It validates
 * the machine config, owns the trajectory queue, and reads the trajectory's
 * tracks at any time.
 *
 * Maxl is the queue's only author: moves are added, replaced and cancelled here,
 * validated against the path as it will stand. Apps read the queue through
 * `maxl.queue` and `maxl.history` (read-only views, trajectory/queueView.ts); the
 * runtime's streamer locks, splits and retires segments inside the core.
 */
import { resolveConfig } from './config/validate.ts';
import type { MaxlConfig, ResolvedConfig } from './config/types.ts';
import { abortable, abortedError, errorAt, isMoveError, MaxlError } from './errors.ts';
import type { Move, ValidatedMove } from './trajectory/moves.ts';
import { TrajectoryQueue, type MoveReceipt } from './trajectory/queue.ts';
import { TrajectoryHistory } from './trajectory/history.ts';
import { readOnlyHistory, readOnlyQueue, type HistoryView, type QueueView } from './trajectory/queueView.ts';
import { Runtime, type DeviceReport, type RecoveryReport, type RuntimeEvent, type StopRecord } from './runtime.ts';
import type { FeedLimit } from './net/linkFeedLimit.ts';
import type { Link } from './net/link.ts';
import type { DeviceInfo, SessionOptions } from './net/session.ts';
import type { StreamerOptions } from './net/streamer.ts';
import type { Scheduler } from './time/scheduler.ts';
import { RealScheduler } from './time/realScheduler.ts';
import type { SensorCapture } from './capture/sensorCapture.ts';
import { captureToCsv } from './capture/csv.ts';
import { restingSample, type TrajectorySample } from './trajectory/tracks.ts';
import { actuatorPosition } from './config/transforms.ts';

export interface MaxlOptions {
  /** mm per motion axis where the machine starts. Default: all zeros. */
  initialPosition?: number[];
  /** The devices' links (WebSerial ports, serialport, simulated links); begin() opens them. */
  links?: Link[];
  /** The author's clock. Default: the wall clock (RealScheduler); tests pass a VirtualScheduler. */
  scheduler?: Scheduler;
  session?: Partial<SessionOptions>;
  streamer?: Partial<StreamerOptions>;
  /**
   * How long begin() syncs clocks before streaming (µs). Default 2 s: after 1 s a
   * young clock model was still off by ~45 µs on a busy link (three boards, event
   * and velocity tracks), enough to put a CoreXY motor at 280 mm/s a third of a
   * step off its plan (core/system/positions.test.ts, lightPainter).
   */
  syncBeforeStart_us?: number;
  /** How many transmitted segments the as-planned history keeps for sampling the past. Default 100 000. */
  historyLimit?: number;
  /**
   * Slow the motion where a link could not carry its segments in time (net/linkFeedLimit.ts).
   * Default true; off, such a job starves its device.
   */
  linkFeedLimit?: boolean;
  /**
   * Before begin() resolves, stream a short dry move to devices that encode every
   * frame and drop it, so that the first real move runs compiled code, not code a
   * JavaScript engine meets for the first time (net/warmUp.ts). For real boards on the
   * wall clock; default false (virtual time does not care).
   */
  warmUp?: boolean;
}

/** How long a call may wait, and how to give up waiting. */
export interface WaitOptions {
  /** Aborting it rejects the wait with a MaxlError of code ABORTED, having changed nothing. */
  signal?: AbortSignal;
}

/** The queue of each Maxl, for the core's own tests and benches (queueOf). */
const queues = new WeakMap<Maxl, TrajectoryQueue>();

export class Maxl {
  readonly config: ResolvedConfig;
  /** The trajectory queue, read-only: segments ahead and their states, the transmitted horizon, events. */
  readonly queue: QueueView;
  /** Transmitted and historical segments, oldest first, as compact records (read-only). */
  readonly history: HistoryView;
  private readonly trajectory: TrajectoryQueue;
  private readonly record: TrajectoryHistory;
  /** End of the last move still waiting for room, if any waits. */
  private pendingTail: number[] = [];
  private pendingCount = 0;
  private closed = false;

  constructor(config: MaxlConfig, options: MaxlOptions = {}) {
    this.config = resolveConfig(config);
    const start = options.initialPosition ?? new Array<number>(this.config.motionAxes.length).fill(0);
    if (start.length !== this.config.motionAxes.length || !start.every(Number.isFinite)) {
      throw new MaxlError('MOVE_DIMENSION', `must give ${this.config.motionAxes.length} finite positions`, 'initialPosition');
    }
    const c = this.config;
    const history = new TrajectoryHistory(c.motionAxes.length, c.actuatorAxes.length, c.eventChannels.length, options.historyLimit ?? 100_000);
    this.record = history;
    this.history = readOnlyHistory(history);
    this.trajectory = new TrajectoryQueue(this.config, start, history);
    this.queue = readOnlyQueue(this.trajectory);
    queues.set(this, this.trajectory);
    this.scheduler = options.scheduler ?? new RealScheduler();
    this.runtimeOptions = options;
  }

  /** Where the next move will start: after the moves waiting for room, or at the queue's tail. */
  get nextMoveStart(): readonly number[] {
    return this.pendingCount > 0 ? this.pendingTail : this.trajectory.tailPosition;
  }

  /**
   * Validates the move at once (a bad move rejects, and nothing is enqueued), then
   * resolves when the queue had room for it. Awaiting each call paces a loop to the
   * machine (paper, Listing 2). Calls that are not awaited keep their order.
   *
   * `signal` gives up a wait for room: the call rejects with a MaxlError of code
   * ABORTED and the move is never queued (a move already queued is not taken back).
   */
  addSegmentToQueue(move: Move, options?: WaitOptions): Promise<MoveReceipt> {
    // (No default `= {}`: that would make an object per call, a million a second here.)
    const signal = options?.signal;
    // Fast path: room now and nobody waiting, and a plain line, appended without a ValidatedMove.
    if (this.pendingCount === 0 && !this.closed && !signal?.aborted && this.trajectory.hasRoom()) {
      const receipt = this.trajectory.appendIfPlainLine(move);
      if (receipt !== null) return Promise.resolve(receipt);
    }
    let validated: ValidatedMove;
    try {
      if (this.closed) throw new MaxlError('QUEUE_CLOSED', 'this MAXL instance was closed');
      if (signal?.aborted) throw abortedError(signal, 'the wait for room in the queue');
      validated = this.trajectory.validate(move, this.nextMoveStart);
    } catch (err) {
      return Promise.reject(err);
    }
    // Room now and nobody waiting, so no extra turn of the event loop.
    if (this.pendingCount === 0 && this.trajectory.hasRoom()) {
      try {
        return Promise.resolve(this.trajectory.appendValidated(validated));
      } catch (err) {
        // A nonlinear transform failing inside the move's subdivision: refused, nothing queued.
        return Promise.reject(err);
      }
    }
    return this.appendWhenRoom(validated, signal);
  }

  /**
   * The batch form of addSegmentToQueue, for callers with many moves at hand (an
   * imported SVG or G-code file, a plotter job): appends moves[from], moves[from + 1],
   * … synchronously for as long as the queue has room, and returns the index of the
   * first move not appended (moves.length when all were): it has room exactly when
   * a single add would not wait (queue.hasRoom()). Each move is validated
   * and queued exactly as addSegmentToQueue would queue it (the same segments, ids
   * and plan), without a promise or a receipt per move, which is most of the cost
   * of a fine path. A bad move throws a MaxlError whose field names it
   * (`moves[i].endPosition`), with the moves before it queued and nothing of it, as
   * a loop of addSegmentToQueue stops there. While moves of addSegmentToQueue calls
   * wait for room it appends nothing (they go first). addSegmentsToQueue waits for
   * room; this never does.
   */
  addSegmentsNow(moves: readonly Move[], from = 0): number {
    this.open();
    if (!Array.isArray(moves)) throw new MaxlError('MOVE_INVALID', 'must be an array of moves', 'moves');
    if (!Number.isInteger(from) || from < 0 || from > moves.length) {
      throw new MaxlError('MOVE_INVALID', `must be an index from 0 to ${moves.length}, got ${String(from)}`, 'from');
    }
    if (this.pendingCount > 0) return from;
    return this.trajectory.appendWhileRoom(moves, from);
  }

  /**
   * Adds every move of `moves` in order, waiting for room as a loop of awaited
   * addSegmentToQueue calls would, and resolves with moves.length once the last is
   * queued. Runs of moves that fit go in synchronously (addSegmentsNow). It rejects
   * at the first bad move (the field names it: `moves[i]…`), with the moves before
   * it queued; `signal` gives up the wait for room (ABORTED), with the moves before
   * the one that waited queued.
   */
  async addSegmentsToQueue(moves: readonly Move[], options?: WaitOptions): Promise<number> {
    let i = this.addSegmentsNow(moves, 0);
    while (i < moves.length) {
      // No room (or earlier callers waiting): this move waits its turn, as a single add does.
      try {
        await this.addSegmentToQueue(moves[i], options);
      } catch (err) {
        throw err instanceof MaxlError && isMoveError(err) ? errorAt(err, `moves[${i}]`) : err;
      }
      i = this.addSegmentsNow(moves, i + 1);
    }
    return i;
  }

  private async appendWhenRoom(validated: ValidatedMove, signal: AbortSignal | undefined): Promise<MoveReceipt> {
    const previousTail = this.pendingTail;
    this.pendingTail = validated.end;
    this.pendingCount++;
    try {
      await this.trajectory.reserveSlot(signal);
    } catch (err) {
      // Given up: the next move starts where this one would have (the last waiting move's end, or the queue's tail).
      if (this.pendingTail === validated.end) this.pendingTail = previousTail;
      throw err;
    } finally {
      this.pendingCount--;
    }
    if (signal?.aborted) {
      // Aborted after the slot came but before this turn: the move is still given up.
      this.trajectory.releaseSlot();
      throw abortedError(signal, 'the wait for room in the queue');
    }
    if (this.closed) {
      this.trajectory.releaseSlot();
      throw new MaxlError('QUEUE_CLOSED', 'this MAXL instance was closed while the move waited for room');
    }
    return this.trajectory.appendValidated(validated, true);
  }

  /**
   * Replaces an untransmitted move (all its segments) by `move`, validated from where
   * that move starts; later moves keep their end positions. For editing the unsent
   * tail point by point (a live stroke's last point moving). Throws SEGMENT_LOCKED
   * once any part of the move was transmitted, CANNOT_STOP_IN_PATH if the moving
   * machine would be left without room to brake, and changes nothing then.
   */
  replaceMove(moveId: number, move: Move): MoveReceipt {
    this.open();
    return this.trajectory.replace(moveId, move);
  }

  /** Cancels an untransmitted move; the moves after it now start where the one before it ended. Refused as replaceMove is. */
  cancelMove(moveId: number): void {
    this.open();
    this.trajectory.cancel(moveId);
  }

  /**
   * Cancels an untransmitted move and every queued move after it: the path ends
   * where the move began. Moves still waiting for room (addSegmentToQueue not yet
   * resolved) are not queued yet, and are not cancelled: abort them through their
   * signal. Refused as replaceMove is.
   */
  cancelMovesFrom(moveId: number): void {
    this.open();
    this.trajectory.cancelMovesFrom(moveId);
  }

  private open(): void {
    if (this.closed) throw new MaxlError('QUEUE_CLOSED', 'this MAXL instance was closed');
  }

  /** Zero-length moves skipped so far (those that set no event: one that does is a 0-s dwell). */
  get skippedZeroLength(): number {
    return this.trajectory.skippedZeroLength;
  }

  /** Refuses further moves. */
  close(): void {
    this.closed = true;
  }

  // --- the distributed runtime ---

  readonly scheduler: Scheduler;
  private runtime: Runtime | null = null;
  private readonly runtimeOptions: MaxlOptions;

  /**
   * Opens a session with every device on `links`, checks the subscriptions against
   * their readers, subscribes them, syncs clocks, and starts streaming the queue.
   */
  async begin(): Promise<DeviceInfo[]> {
    if (this.runtime) throw new MaxlError('NOT_STARTED', 'begin() was already called');
    const o = this.runtimeOptions;
    const host = { config: this.config, queue: this.trajectory, sample: (t_us: number) => this.sample(t_us) };
    this.runtime = new Runtime(host, {
      links: o.links ?? [],
      scheduler: this.scheduler,
      session: o.session,
      streamer: o.streamer,
      syncBeforeStart_us: o.syncBeforeStart_us,
      linkFeedLimit: o.linkFeedLimit,
      warmUp: o.warmUp,
    });
    for (const l of this.pendingListeners) this.runtime.on(l);
    return this.runtime.begin();
  }

  /** Listens to devices, errors, stops and samples. */
  on(listener: (e: RuntimeEvent) => void): () => void {
    if (this.runtime) return this.runtime.on(listener);
    this.pendingListeners.push(listener);
    return () => {
      this.pendingListeners = this.pendingListeners.filter((l) => l !== listener);
    };
  }
  private pendingListeners: Array<(e: RuntimeEvent) => void> = [];

  private started(): Runtime {
    if (!this.runtime) throw new MaxlError('NOT_STARTED', 'call begin() first');
    return this.runtime;
  }

  devices(): DeviceReport[] {
    return this.runtime?.devices() ?? [];
  }

  /**
   * The floor the links put on every segment's duration (null before begin()): a
   * segment of length L then runs at most L / floor fast. `device` is the one whose
   * link sets it; minSegment_us 0 means no link limits the motion.
   */
  get feedLimit(): Readonly<FeedLimit> | null {
    return this.runtime?.feedLimit ?? null;
  }

  /** Brings the machine to rest on the path as fast as its limits allow, and holds. */
  pause(): Promise<void> {
    return this.started().pause();
  }

  /** Continues after pause(). (After a stop off the plan, see reconnect() and resumeJob().) */
  resume(): void {
    this.started().resume();
  }

  /** Stops on the path as fast as the limits allow, and drops every move after the stop. */
  cancel(): Promise<void> {
    return this.started().cancel();
  }

  /**
   * Emergency stop: every device stops where it is, now. Nothing more streams; the
   * rest of the job stays queued for reconnect() and resumeJob(), or discardJob().
   */
  halt(): Promise<void> {
    return this.started().halt();
  }

  // --- recovery (docs/architecture.md, "Recovery") ---

  /**
   * Why the machine stopped off its plan (a link lost, a device restarted, a HALT,
   * a refused segment), until the job resumes or is dropped; null while all is well.
   * While it is set, whenIdle() rejects (with the refusal's error, else
   * RECOVERY_ORDER), resume() refuses with RECOVERY_ORDER, pause() and cancel()
   * resolve and change nothing; moves added meanwhile wait at the end of the job.
   */
  get stopped(): Readonly<StopRecord> | null {
    return this.runtime?.stopped ?? null;
  }

  /**
   * After a stop off the plan: re-opens the links (the same ones, or `links` in
   * their place), asks every board where it stopped, re-syncs clocks, and rebuilds
   * the queue from there: the rest of the job, nothing lost, nothing run twice.
   * Nothing moves until resumeJob() or discardJob(). Refuses with RECOVERY_ORDER
   * out of order, DEVICE_UNAVAILABLE if a board does not answer (then try again).
   */
  reconnect(links?: Link[]): Promise<RecoveryReport> {
    return this.started().reconnect(links);
  }

  /** After reconnect(): runs the rest of the job from where the machine stopped. */
  resumeJob(): void {
    this.started().resumeJob();
  }

  /** After reconnect(): drops the rest of the job; the machine stays where it stopped. */
  discardJob(): void {
    this.started().discardJob();
  }

  /**
   * Resolves when everything queued has run (or the machine holds at rest after a
   * pause). `signal` gives up the wait: a MaxlError of code ABORTED; the machine goes on.
   */
  whenIdle(options: WaitOptions = {}): Promise<void> {
    return abortable(this.started().whenIdle(), options.signal, 'the wait for the machine to be idle');
  }

  async end(): Promise<void> {
    await this.runtime?.end();
  }

  /** The machine now, by the author's clock: every track, and the worst clock-sync error over the devices. */
  estimate(): TrajectorySample & { time_us: number; syncError_us: number } {
    const time_us = this.scheduler.now();
    return { ...this.sample(time_us), time_us, syncError_us: this.runtime?.syncError_us ?? NaN };
  }

  /** Sensor captures so far, by "device/reader". */
  get captures(): ReadonlyMap<string, SensorCapture> {
    return this.runtime?.captures ?? new Map();
  }

  /**
   * A capture as CSV (capture/csv.ts), each sample joined with the planned position,
   * velocity and acceleration at its time; cells that could read as formulas neutralised.
   * Samples older than the as-planned history's horizon (historyLimit segments back) get
   * empty planned cells rather than a guess.
   */
  captureCsv(key: string, channelNames?: string[]): string {
    const capture = this.captures.get(key);
    if (!capture) throw new MaxlError('CONFIG_INVALID', `no capture "${key}" (captures: ${[...this.captures.keys()].join(', ') || 'none'})`, 'capture');
    const horizon = this.record.horizon_us;
    return captureToCsv(capture, { sample: (t) => (t < horizon ? null : this.sample(t)), motionAxes: this.config.motionAxes, channelNames });
  }

  /** µs of motion the streamer keeps ahead of the machine (2·RTT plus a margin). */
  get lead_us(): number {
    return this.runtime?.lead_us ?? NaN;
  }

  /**
   * Every track at author time t_us, over the transmitted trajectory. Before it
   * the machine rests at its start; between jobs, and after, at the last end.
   */
  sample(t_us: number): TrajectorySample {
    const s = this.record.sample(t_us);
    if (s !== null) return s;
    const p = this.trajectory.tailPosition;
    return restingSample(p, actuatorPosition(this.config.transforms, p));
  }

  /** One track's value at author time t_us: a motion or actuator axis, velocity, acceleration or an event channel. */
  trackValue(track: string, t_us: number): number {
    const info = this.config.tracks.find((t) => t.name === track);
    if (!info) throw new MaxlError('CONFIG_INVALID', `"${track}" is not a track`, 'track');
    if (info.kind === 'event') return this.eventValue(track, t_us);
    const s = this.sample(t_us);
    if (info.kind === 'velocity') return s.speed;
    if (info.kind === 'acceleration') return s.pathAcceleration;
    const m = this.config.motionAxes.indexOf(track);
    return m >= 0 ? s.position[m] : s.actuator[this.config.actuatorAxes.indexOf(track)];
  }

  /** An event channel's value at author time t_us: the last value set at or before t. */
  eventValue(channel: string, t_us: number): number {
    const c = this.config.eventChannels.indexOf(channel);
    if (c < 0) throw new MaxlError('CONFIG_INVALID', `"${channel}" is not an event channel`, 'channel');
    return this.record.eventValue(c, t_us);
  }
}

/**
 * The queue behind `maxl`, with its executing and editing methods: for the core's
 * own tests and benches, which drain a queue without devices. Not part of the
 * public API (core/index.ts does not export it): apps read `maxl.queue` and author
 * through Maxl.
 */
export function queueOf(maxl: Maxl): TrajectoryQueue {
  return queues.get(maxl) as TrajectoryQueue;
}

export function createMAXL(config: MaxlConfig, options?: MaxlOptions): Maxl {
  return new Maxl(config, options);
}
