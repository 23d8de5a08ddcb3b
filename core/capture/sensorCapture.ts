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
 */
import type { ClockMap } from '../net/clockMap.ts';
import type { MessageOf } from '../net/messages.ts';
import { SampleGapDetector, type SampleGap } from './sampleGaps.ts';

export type { SampleGap } from './sampleGaps.ts';

/** Float64 columns that grow by doubling. */
class Column {
  data = new Float64Array(1024);
  ensure(n: number): void {
    if (n <= this.data.length) return;
    const grown = new Float64Array(Math.max(n, this.data.length * 2));
    grown.set(this.data);
    this.data = grown;
  }
}

export class SensorCapture {
  readonly device: string;
  readonly reader: string;
  readonly channels: number;
  private readonly times = new Column();
  private readonly deviceTimes = new Column();
  private readonly batches = new Column();
  private readonly indices = new Column();
  private readonly sequence = new Column();
  private readonly values: Column[];
  private count = 0;
  private samplesBefore = 0;
  private readonly detector = new SampleGapDetector();
  /** Every gap and duplicate, in order. */
  readonly gaps: SampleGap[] = [];

  constructor(device: string, reader: string, channels: number) {
    this.device = device;
    this.reader = reader;
    this.channels = channels;
    this.values = Array.from({ length: channels }, () => new Column());
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
    const n = this.count + 1;
    for (const c of [this.times, this.deviceTimes, this.batches, this.indices, this.sequence, ...this.values]) c.ensure(n);
    const k = this.count;
    this.times.data[k] = t;
    this.deviceTimes.data[k] = device;
    this.batches.data[k] = batch;
    this.indices.data[k] = index;
    this.sequence.data[k] = this.samplesBefore++;
    for (let c = 0; c < this.channels; c++) this.values[c].data[k] = values[c];
    this.count = n;
  }

  /** Author µs of each sample (a view, valid until the next add). */
  timeColumn(): Float64Array {
    return this.times.data.subarray(0, this.count);
  }

  /** The device's u32 µs stamp of each sample. */
  deviceTimeColumn(): Float64Array {
    return this.deviceTimes.data.subarray(0, this.count);
  }

  /** The batch number of each sample (the wire's u16, unwrapped). */
  batchColumn(): Float64Array {
    return this.batches.data.subarray(0, this.count);
  }

  /** Each sample's index in its batch. */
  indexColumn(): Float64Array {
    return this.indices.data.subarray(0, this.count);
  }

  /** Each sample's number: samples the device took before it, lost ones included. */
  sequenceColumn(): Float64Array {
    return this.sequence.data.subarray(0, this.count);
  }

  /** One channel's values (a view, valid until the next add). */
  channel(c: number): Float64Array {
    return this.values[c].data.subarray(0, this.count);
  }
}
