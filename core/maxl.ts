/**
 * createMAXL: the author object of the paper (Listings 1, 2 and 5). It validates
 * the machine config, owns the trajectory queue, and reads the trajectory's
 * tracks at any time.
 */
import { resolveConfig } from './config/validate.ts';
import type { MaxlConfig, ResolvedConfig } from './config/types.ts';
import { MaxlError } from './errors.ts';
import type { Move, ValidatedMove } from './trajectory/moves.ts';
import { TrajectoryQueue, type MoveReceipt } from './trajectory/queue.ts';
import { TrajectoryHistory } from './trajectory/history.ts';
import { restingSample, type TrajectorySample } from './trajectory/tracks.ts';
import { actuatorPosition } from './trajectory/transforms.ts';

export interface MaxlOptions {
  /** mm per motion axis where the machine starts. Default: all zeros. */
  initialPosition?: number[];
  /** How many transmitted segments the as-planned history keeps for sampling the past. Default 100 000. */
  historyLimit?: number;
}

export class Maxl {
  readonly config: ResolvedConfig;
  readonly queue: TrajectoryQueue;
  /** Transmitted and historical segments, oldest first, as compact records. */
  readonly history: TrajectoryHistory;
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
    this.history = new TrajectoryHistory(c.motionAxes.length, c.actuatorAxes.length, c.eventChannels.length, options.historyLimit ?? 100_000);
    this.queue = new TrajectoryQueue(this.config, start, (seg) => this.history.push(seg));
  }

  /** Where the next move will start: after the moves waiting for room, or at the queue's tail. */
  get nextMoveStart(): readonly number[] {
    return this.pendingCount > 0 ? this.pendingTail : this.queue.tailPosition;
  }

  /**
   * Validates the move at once (a bad move rejects, and nothing is enqueued), then
   * resolves when the queue had room for it. Awaiting each call paces a loop to the
   * machine (paper, Listing 2). Calls that are not awaited keep their order.
   */
  addSegmentToQueue(move: Move): Promise<MoveReceipt> {
    let validated: ValidatedMove;
    try {
      if (this.closed) throw new MaxlError('QUEUE_CLOSED', 'this MAXL instance was closed');
      validated = this.queue.validate(move, this.nextMoveStart);
    } catch (err) {
      return Promise.reject(err);
    }
    // Fast path: room now and nobody waiting, so no extra turn of the event loop.
    if (this.pendingCount === 0 && this.queue.hasRoom()) return Promise.resolve(this.queue.appendValidated(validated));
    return this.appendWhenRoom(validated);
  }

  private async appendWhenRoom(validated: ValidatedMove): Promise<MoveReceipt> {
    this.pendingTail = validated.end;
    this.pendingCount++;
    try {
      await this.queue.reserveSlot();
    } finally {
      this.pendingCount--;
    }
    if (this.closed) throw new MaxlError('QUEUE_CLOSED', 'this MAXL instance was closed while the move waited for room');
    return this.queue.appendValidated(validated, true);
  }

  /** Zero-length moves skipped so far. */
  get skippedZeroLength(): number {
    return this.queue.skippedZeroLength;
  }

  /** Refuses further moves. */
  close(): void {
    this.closed = true;
  }

  /**
   * Every track at author time t_us, over the transmitted trajectory. Before it
   * the machine rests at its start; between jobs, and after, at the last end.
   */
  sample(t_us: number): TrajectorySample {
    const s = this.history.sample(t_us);
    if (s !== null) return s;
    const p = this.queue.tailPosition;
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
    return this.history.eventValue(c, t_us);
  }
}

export function createMAXL(config: MaxlConfig, options?: MaxlOptions): Maxl {
  return new Maxl(config, options);
}
