/**
 * Sensor capture: samples a device stamped with its own clock, mapped into author
 * time through that device's clock model, kept in growable columns, with every gap
 * in the batches detected (sampleGaps.ts) and kept.
 *
 * Per sample it keeps: the author time (µs), the device's own u32 time stamp, the
 * batch number (unwrapped past the wire's u16), the index in that batch, and the
 * sample number: the count of samples the device took before it, lost ones included
 * (so a gap of n lost samples shows as a jump of n + 1 in it, and nowhere else).
 *
 * A SAMPLES batch gives t0 (device µs) and each sample's dt from the one before;
 * device times are unwrapped against the author's clock model, so a capture can
 * cross the 71.6-minute wrap of a u32 µs counter.
 *
 * The columns grow by chunks (chunkedColumn.ts): a sample added never copies the
 * others. Reading a column whole makes one copy, kept until the next batch.
 */
import type { ClockMap } from '../net/clockMap.ts';
import type { MessageOf } from '../net/messages.ts';
import { SampleGapDetector, type SampleGap } from './sampleGaps.ts';
import { ChunkedColumn } from './chunkedColumn.ts';

export type { SampleGap } from './sampleGaps.ts';

export class SensorCapture {
  readonly device: string;
  readonly reader: string;
  readonly channels: number;
  private readonly times = new ChunkedColumn();
  private readonly deviceTimes = new ChunkedColumn();
  private readonly batches = new ChunkedColumn();
  private readonly indices = new ChunkedColumn();
  private readonly sequence = new ChunkedColumn();
  private readonly values: ChunkedColumn[];
  private count = 0;
  private samplesBefore = 0;
  private readonly detector = new SampleGapDetector();
  /** Every gap and duplicate, in order. */
  readonly gaps: SampleGap[] = [];

  constructor(device: string, reader: string, channels: number) {
    this.device = device;
    this.reader = reader;
    this.channels = channels;
    this.values = Array.from({ length: channels }, () => new ChunkedColumn());
  }

  get size(): number {
    return this.count;
  }

  /** Batches lost in all. */
  get lostBatches(): number {
    return this.gaps.reduce((n, g) => n + g.batches, 0);
  }

  /** Samples lost in all. */
  get lostSamples(): number {
    return this.gaps.reduce((n, g) => n + g.samples, 0);
  }

  /** Duplicate batches dropped. */
  get duplicateBatches(): number {
    return this.gaps.filter((g) => g.kind === 'duplicate').length;
  }

  /**
   * Adds one SAMPLES batch. `clock` maps the device's clock to author time, and
   * `near_us` (the author time it arrived) picks the right 2³² wrap. Returns the gap
   * (lost batches before it, or the batch itself a duplicate and dropped), or null.
   */
  add(batch: MessageOf<'SAMPLES'>, clock: ClockMap, near_us: number): SampleGap | null {
    const deviceTimes: number[] = [];
    let t = batch.t0;
    for (const s of batch.samples) {
      t = (t + s.dt) >>> 0;
      deviceTimes.push(t);
    }
    const authorTimes = deviceTimes.map((d) => clock.toAuthor(d, near_us));
    const verdict = this.detector.judge(batch.sampleSeq, authorTimes, deviceTimes);
    const gap = verdict.gap ? { ...verdict.gap, index: this.count } : null;
    if (gap) this.gaps.push(gap);
    if (gap?.kind === 'duplicate') return gap;
    this.detector.accept(batch.sampleSeq, verdict.batch, authorTimes, deviceTimes, gap === null);
    if (gap) this.samplesBefore += gap.samples;
    batch.samples.forEach((s, k) => this.push(authorTimes[k], deviceTimes[k], verdict.batch, k, s.values));
    return gap;
  }

  private push(t: number, device: number, batch: number, index: number, values: readonly number[]): void {
    this.times.push(t);
    this.deviceTimes.push(device);
    this.batches.push(batch);
    this.indices.push(index);
    this.sequence.push(this.samplesBefore++);
    for (let c = 0; c < this.channels; c++) this.values[c].push(values[c]);
    this.count++;
  }

  /** Author µs of each sample (one copy, the same array until the next add). */
  timeColumn(): Float64Array {
    return this.times.toArray();
  }

  /** The device's u32 µs stamp of each sample. */
  deviceTimeColumn(): Float64Array {
    return this.deviceTimes.toArray();
  }

  /** The batch number of each sample (the wire's u16, unwrapped). */
  batchColumn(): Float64Array {
    return this.batches.toArray();
  }

  /** Each sample's index in its batch. */
  indexColumn(): Float64Array {
    return this.indices.toArray();
  }

  /** Each sample's number: samples the device took before it, lost ones included. */
  sequenceColumn(): Float64Array {
    return this.sequence.toArray();
  }

  /** One channel's values (one copy, the same array until the next add). */
  channel(c: number): Float64Array {
    return this.values[c].toArray();
  }

  /** Samples [from, to) of one column into a new array: no copy of the rest. */
  slice(column: 'time' | 'deviceTime' | 'batch' | 'index' | 'sequence' | number, from: number, to: number): Float64Array {
    const source = typeof column === 'number' ? this.values[column] : { time: this.times, deviceTime: this.deviceTimes, batch: this.batches, index: this.indices, sequence: this.sequence }[column];
    if (!source) throw new RangeError(`the capture has no column ${column} (it has ${this.channels} channels)`);
    return source.copyInto(new Float64Array(Math.max(0, to - from)), from, to);
  }
}
