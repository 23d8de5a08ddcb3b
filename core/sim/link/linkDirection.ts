/**
 * One direction of a simulated USB serial link: bytes written at some author
 * time come out, in order, at a later time, possibly changed or missing.
 *
 * Everything is decided when the bytes are written, so a write costs at most
 * one scheduler timer (the delivery), however many frames it spans:
 *
 *   1. Frame assignment. A write at t joins the first frame starting after t
 *      (usbFrames.ts), or the last frame already holding data if that one is
 *      later and not full; it spills into following frames once a frame holds
 *      `bytesPerFrame` bytes. This is the bandwidth limit, and the 0..1 ms
 *      quantisation of USB full speed.
 *   2. Packets. The part of the write that rides in one frame is cut into
 *      packets of at most `packetBytes`. Each packet is lost whole with
 *      probability `lossProbability`; each byte of a surviving packet is
 *      corrupted with probability `corruptionProbability`.
 *   3. Delivery at frame start + baseDelay + jitter (uniform in
 *      [jitterMin, jitterMax]), but never before the previous delivery: USB and
 *      a serial driver never reorder bytes, so jitter only bunches them.
 *   4. A cut drops whatever is written at or after the cut time, and whatever
 *      would be delivered at or after it.
 */
import type { Scheduler } from '../../time/scheduler.ts';
import type { LinkDirectionConfig } from './linkConfig.ts';
import { emptyCounters, type LinkDirectionCounters } from './linkCounters.ts';
import { nextFrameStart } from './usbFrames.ts';

export interface FrameShape {
  framePeriod_us: number;
  packetBytes: number;
  bytesPerFrame: number;
}

export class LinkDirection {
  readonly counters: LinkDirectionCounters = emptyCounters();
  private config: LinkDirectionConfig;
  /** Start time of the latest frame holding data, and how many bytes it holds. */
  private lastFrame_us = -Infinity;
  private lastFrameBytes = 0;
  /** Time of the latest delivery scheduled (deliveries keep their order). */
  private lastDelivery_us = -Infinity;

  constructor(
    private readonly scheduler: Scheduler,
    private readonly frame: FrameShape,
    config: LinkDirectionConfig,
    private readonly random: () => number,
    /** Receives bytes at their delivery time. */
    private readonly deliver: (bytes: Uint8Array, at_us: number) => void,
    /** The author time at which the link is cut (Infinity if never). */
    private readonly cutAt: () => number,
  ) {
    this.config = { ...config };
  }

  get settings(): Readonly<LinkDirectionConfig> {
    return this.config;
  }

  /** Changes delays, jitter or fault rates from now on (bytes already in flight keep theirs). */
  configure(change: Partial<LinkDirectionConfig>): void {
    this.config = { ...this.config, ...change };
  }

  /** Bytes written by the sender at author time `written_us` (at most a little before now). */
  submit(bytes: Uint8Array, written_us: number): void {
    const c = this.counters;
    c.bytesWritten += bytes.length;
    if (bytes.length === 0) return;
    if (written_us >= this.cutAt()) {
      c.bytesCut += bytes.length;
      return;
    }
    let offset = 0;
    while (offset < bytes.length) {
      // 1. Frame assignment.
      const first = nextFrameStart(written_us, this.frame.framePeriod_us);
      if (this.lastFrame_us < first) {
        this.lastFrame_us = first;
        this.lastFrameBytes = 0;
      } else if (this.lastFrameBytes >= this.frame.bytesPerFrame) {
        this.lastFrame_us += this.frame.framePeriod_us;
        this.lastFrameBytes = 0;
      }
      if (this.lastFrameBytes === 0) c.framesUsed++;
      const take = Math.min(bytes.length - offset, this.frame.bytesPerFrame - this.lastFrameBytes);
      const chunk = bytes.slice(offset, offset + take);
      offset += take;
      this.lastFrameBytes += take;
      // 2. Packets: loss and corruption.
      const survivors = this.applyFaults(chunk);
      // 3. Delivery time, in order.
      const jitter = this.config.jitterMin_us + (this.config.jitterMax_us - this.config.jitterMin_us) * this.random();
      const at = Math.max(this.lastFrame_us + this.config.baseDelay_us + jitter, this.lastDelivery_us);
      if (survivors.length === 0) continue;
      this.lastDelivery_us = at;
      this.scheduler.at(at, () => this.arrive(survivors, at, written_us));
    }
  }

  private applyFaults(chunk: Uint8Array): Uint8Array {
    const c = this.counters;
    const { lossProbability, corruptionProbability } = this.config;
    const kept: Uint8Array[] = [];
    for (let p = 0; p < chunk.length; p += this.frame.packetBytes) {
      const packet = chunk.subarray(p, Math.min(chunk.length, p + this.frame.packetBytes));
      c.packetsSent++;
      if (lossProbability > 0 && this.random() < lossProbability) {
        c.packetsLost++;
        c.bytesLost += packet.length;
        continue;
      }
      if (corruptionProbability > 0) {
        for (let i = 0; i < packet.length; i++) {
          if (this.random() < corruptionProbability) {
            // xor with 1..255: the byte always changes.
            packet[i] ^= 1 + Math.floor(this.random() * 255);
            c.bytesCorrupted++;
          }
        }
      }
      kept.push(packet);
    }
    if (kept.length === 1) return kept[0];
    const out = new Uint8Array(kept.reduce((n, k) => n + k.length, 0));
    let o = 0;
    for (const k of kept) {
      out.set(k, o);
      o += k.length;
    }
    return out;
  }

  private arrive(bytes: Uint8Array, at_us: number, written_us: number): void {
    const c = this.counters;
    if (at_us >= this.cutAt()) {
      c.bytesCut += bytes.length;
      return;
    }
    c.bytesDelivered += bytes.length;
    const latency = at_us - written_us;
    c.latencyMin_us = Math.min(c.latencyMin_us, latency);
    c.latencyMax_us = Math.max(c.latencyMax_us, latency);
    c.latencySum_us += latency;
    c.chunksDelivered++;
    this.deliver(bytes, at_us);
  }
}
