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
import type { Segment } from './trajectory/segment.ts';
import { restingSample, sampleTimeline, segmentIndexAt, type TrajectorySample } from './trajectory/tracks.ts';
import { actuatorPosition } from './trajectory/transforms.ts';

export interface MaxlOptions {
  /** mm per motion axis where the machine starts. Default: all zeros. */
  initialPosition?: number[];
  /** How many transmitted segments to keep for sampling the past. Default 100 000. */
  historyLimit?: number;
}

export class Maxl {
  readonly config: ResolvedConfig;
  readonly queue: TrajectoryQueue;
  /** Transmitted and historical segments, oldest first, at most historyLimit. */
  private timeline: Segment[] = [];
  private timelineHead = 0;
  private readonly historyLimit: number;
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
    this.historyLimit = options.historyLimit ?? 100_000;
    this.queue = new TrajectoryQueue(this.config, start);
    this.queue.subscribe((event) => {
      if (event.type === 'transmitted') this.recordTransmitted(event.segments);
    });
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
  async addSegmentToQueue(move: Move): Promise<MoveReceipt> {
    if (this.closed) throw new MaxlError('QUEUE_CLOSED', 'this MAXL instance was closed');
    const validated: ValidatedMove = this.queue.validate(move, this.nextMoveStart);
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
    const segs = this.timeline;
    const s = sampleTimeline(segs, this.timelineHead, (i) => segs[i].startTime_us, t_us, 1e-6);
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
    const segs = this.timeline;
    const found = segmentIndexAt(this.timelineHead, segs.length, (i) => segs[i].startTime_us, t_us);
    if (found < 0) return 0;
    const seg = segs[found];
    let value = this.queue.eventValuesAtStart(seg)?.[c] ?? 0;
    const local = (t_us - seg.startTime_us) * 1e-6;
    for (const track of this.queue.eventTracksOf(seg)) {
      if (track.channel !== c) continue;
      for (let k = 0; k < track.times.length && track.times[k] <= local; k++) value = track.values[k];
    }
    return value;
  }

  private recordTransmitted(segments: readonly Segment[]): void {
    for (const seg of segments) this.timeline.push(seg);
    const excess = this.timeline.length - this.timelineHead - this.historyLimit;
    if (excess > 0) this.timelineHead += excess;
    if (this.timelineHead > 4096 && this.timelineHead * 2 > this.timeline.length) {
      this.timeline = this.timeline.slice(this.timelineHead);
      this.timelineHead = 0;
    }
  }
}

export function createMAXL(config: MaxlConfig, options?: MaxlOptions): Maxl {
  return new Maxl(config, options);
}
