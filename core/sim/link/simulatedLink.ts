/**
 * A full-duplex simulated serial link between the author and one device.
 *
 *   author side:  a core/net Link (readable/writable web streams), which the
 *                 runtime cannot tell from WebSerial;
 *   device side:  a DevicePort the wasm device host writes to and receives
 *                 from, with author-time stamps.
 *
 * Each direction is a LinkDirection (USB frame timing, delay, jitter, faults).
 * A cut, at a configured time or on command, stops everything either way.
 */
import type { Link } from '../../net/link.ts';
import type { Scheduler } from '../../time/scheduler.ts';
import { SimError } from '../errors.ts';
import { deriveSeed, seededRandom } from '../../random.ts';
import { resolveLinkConfig, type LinkConfig, type LinkDirectionConfig, type LinkOverrides } from './linkConfig.ts';
import type { LinkDirectionCounters } from './linkCounters.ts';
import { LinkDirection } from './linkDirection.ts';

/** The device's end of a link. */
export interface DevicePort {
  /** Bytes the device wrote at author time `written_us` (at most a little before now). */
  send(bytes: Uint8Array, written_us: number): void;
  /** Sets the receiver of bytes arriving at the device; `at_us` is the author time of arrival. */
  onReceive(handler: (bytes: Uint8Array, at_us: number) => void): void;
}

export interface LinkReport {
  label: string;
  cutAt_us: number;
  toDevice: LinkDirectionCounters;
  toAuthor: LinkDirectionCounters;
}

export class SimulatedLink {
  readonly config: LinkConfig;
  /** The author's end: hand this to the runtime. */
  readonly link: Link;
  /** The device's end: the wasm device host uses this. */
  readonly device: DevicePort;
  private readonly toDevice: LinkDirection;
  private readonly toAuthor: LinkDirection;
  private cutAt_us: number;
  private receiver: ((bytes: Uint8Array, at_us: number) => void) | null = null;
  private readableController!: ReadableStreamDefaultController<Uint8Array>;
  private closed = false;

  constructor(
    private readonly scheduler: Scheduler,
    readonly label: string,
    overrides: LinkOverrides = {},
  ) {
    this.config = resolveLinkConfig(overrides);
    this.cutAt_us = this.config.cutAt_us;
    const cutAt = () => this.cutAt_us;
    this.toDevice = new LinkDirection(
      scheduler,
      this.config,
      this.config.toDevice,
      seededRandom(deriveSeed(this.config.seed, `${label}/toDevice`)),
      (bytes, at) => this.receiver?.(bytes, at),
      cutAt,
    );
    this.toAuthor = new LinkDirection(
      scheduler,
      this.config,
      this.config.toAuthor,
      seededRandom(deriveSeed(this.config.seed, `${label}/toAuthor`)),
      (bytes) => {
        if (!this.closed) this.readableController.enqueue(bytes);
      },
      cutAt,
    );
    const readable = new ReadableStream<Uint8Array>({
      start: (c) => (this.readableController = c),
      // A reader that cancels (a port closed by the workbench) ends the link: nothing is enqueued after.
      cancel: () => {
        this.closed = true;
      },
    });
    const writable = new WritableStream<Uint8Array>({
      write: (chunk) => {
        if (this.closed) throw new SimError('LINK_CLOSED', `${label}: write after the link was closed`);
        // Copy: the writer may reuse its buffer once the write resolves.
        this.toDevice.submit(chunk.slice(), this.scheduler.now());
      },
    });
    this.link = {
      readable,
      writable,
      label,
      bytesPerSecond: (this.config.bytesPerFrame * 1e6) / this.config.framePeriod_us,
      close: () => this.close(),
    };
    this.device = {
      send: (bytes, written_us) => this.toAuthor.submit(bytes.slice(), written_us),
      onReceive: (handler) => (this.receiver = handler),
    };
  }

  /** Cuts the link at `at_us` (default: now). Nothing written or due from then on passes, either way. */
  cut(at_us: number = this.scheduler.now()): void {
    this.cutAt_us = Math.min(this.cutAt_us, at_us);
  }

  /** Undoes a cut from now on (what was dropped stays dropped), like plugging the cable back in. */
  restore(): void {
    this.cutAt_us = Infinity;
  }

  isCut(at_us: number = this.scheduler.now()): boolean {
    return at_us >= this.cutAt_us;
  }

  /** Changes one direction's delays, jitter, corruption or loss from now on. */
  configure(direction: 'toDevice' | 'toAuthor', change: Partial<LinkDirectionConfig>): void {
    (direction === 'toDevice' ? this.toDevice : this.toAuthor).configure(change);
  }

  report(): LinkReport {
    return { label: this.label, cutAt_us: this.cutAt_us, toDevice: { ...this.toDevice.counters }, toAuthor: { ...this.toAuthor.counters } };
  }

  /** Ends the author's readable stream; later writes fail with LINK_CLOSED. */
  async close(): Promise<void> {
    if (this.closed) return;
    this.closed = true;
    try {
      this.readableController.close();
    } catch {
      // Already closed or errored by a reader's cancel: nothing left to end.
    }
  }
}
