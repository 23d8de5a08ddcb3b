/**
 * Sensor capture: samples a device stamped with its own clock, mapped into author
 * time through that device's clock model, kept in growable columns (one Float64Array
 * of times, one Float32Array per channel), with sequence gaps counted.
 *
 * A SAMPLES batch gives t0 (device µs) and each sample's dt from the one before;
 * device times are unwrapped against the author's clock model, so a capture can
 * cross the 71.6-minute wrap of a u32 µs counter.
 */
import type { ClockMap } from '../net/clockMap.ts';
import type { MessageOf } from '../net/messages.ts';

export interface CaptureGap {
  /** batches missing before this one */
  missing: number;
  /** author µs of the first sample after the gap */
  at_us: number;
}

export class SensorCapture {
  readonly device: string;
  readonly reader: string;
  readonly channels: number;
  private times: Float64Array = new Float64Array(1024);
  private values: Float32Array[];
  private count = 0;
  private lastSeq: number | null = null;
  readonly gaps: CaptureGap[] = [];

  constructor(device: string, reader: string, channels: number) {
    this.device = device;
    this.reader = reader;
    this.channels = channels;
    this.values = Array.from({ length: channels }, () => new Float32Array(1024));
  }

  get size(): number {
    return this.count;
  }

  /** Samples missing in all, from sequence gaps (batches × the batch size seen). */
  get missingBatches(): number {
    return this.gaps.reduce((n, g) => n + g.missing, 0);
  }

  /**
   * Adds one SAMPLES batch. `clock` maps the device's clock to author time, and
   * `near_us` (the author time it arrived) picks the right 2³² wrap.
   */
  add(batch: MessageOf<'SAMPLES'>, clock: ClockMap, near_us: number): void {
    if (this.lastSeq !== null) {
      const missing = (batch.sampleSeq - this.lastSeq - 1 + 0x10000) & 0xffff;
      if (missing > 0 && missing < 0x8000) this.gaps.push({ missing, at_us: NaN });
    }
    this.lastSeq = batch.sampleSeq;
    let t = batch.t0;
    const gapIndex = this.gaps.length - 1;
    batch.samples.forEach((s, k) => {
      t = (t + s.dt) >>> 0;
      const author = clock.toAuthor(t, near_us);
      if (k === 0 && gapIndex >= 0 && Number.isNaN(this.gaps[gapIndex].at_us)) this.gaps[gapIndex].at_us = author;
      this.push(author, s.values);
    });
  }

  private push(t: number, values: readonly number[]): void {
    if (this.count === this.times.length) {
      const times = new Float64Array(this.times.length * 2);
      times.set(this.times);
      this.times = times;
      this.values = this.values.map((v) => {
        const grown = new Float32Array(v.length * 2);
        grown.set(v);
        return grown;
      });
    }
    this.times[this.count] = t;
    for (let c = 0; c < this.channels; c++) this.values[c][this.count] = values[c];
    this.count++;
  }

  /** Author µs of each sample (a view, valid until the next add). */
  timeColumn(): Float64Array {
    return this.times.subarray(0, this.count);
  }

  /** One channel's values (a view, valid until the next add). */
  channel(c: number): Float32Array {
    return this.values[c].subarray(0, this.count);
  }
}
