/**
 * Sample loss detection for a sensor reader's SAMPLES batches, wrap-safe and exact.
 *
 * The wire numbers batches, not samples, with a u16 `sampleSeq` (docs/protocol.md §4).
 * From the sequence alone the number of batches missing between two received ones is
 * known only modulo 2¹⁶:
 *
 *   r = (seq − lastSeq − 1) mod 65 536,   missing batches ∈ { r, r + 65 536, r + 2·65 536, … }
 *
 * so a gap of exactly 65 536 batches looks like none, a duplicate (seq = lastSeq) looks
 * like 65 535 lost, and the old rule "r < 32 768 or ignore" missed every gap of 32 768
 * batches or more. The batches also carry the device time of every sample, and the time
 * that passed across the gap says how many samples (so how many batches) fit in it:
 *
 *   Δ = d(first sample after) − d(last sample before)       (device µs: the u32 stamps'
 *       difference, plus the multiple of 2³² that the author times' difference says)
 *   samples missing  s = round(Δ / P) − 1                     P = the reader's sample period
 *   batches missing  b = the candidate r + 65 536·k nearest to s / B,   B = samples per batch
 *
 * Δ and P are counted on the device's own clock because that is where the sensor is
 * paced: a pacer that adds its period to the last due time (the Accelerometer example's
 * SamplePacer) stamps samples exactly P device µs apart, so Δ / P is an integer however
 * long the gap. (Author times would not do: a 1 ppm error in the clock model's rate is
 * 3.6 ms an hour, a third of a sample at 100 Hz.) P and B are the medians over the
 * recent samples and batches (a batch goes out when full, so B is steady). A candidate is chosen by time
 * only between multiples of 65 536 batches, i.e. hours apart at any real rate, so a clock
 * error of milliseconds cannot pick the wrong one. When b > 0 at least one sample went
 * with each lost batch, so s is raised to b if the time said less (a pacer that skipped).
 * When b = 0 nothing was lost, whatever the time says: a device that sampled late lost
 * nothing.
 *
 * A batch whose first sample is not later than the last sample kept is a duplicate (or
 * out of order): it is dropped and reported, never merged.
 */

/** What happened between two batches of one reader. */
export interface SampleGap {
  kind: 'lost' | 'duplicate';
  /** batches missing (0 for a duplicate) */
  batches: number;
  /** samples missing (0 for a duplicate; the samples dropped are `droppedSamples`) */
  samples: number;
  /** samples of a duplicate batch that were dropped */
  droppedSamples: number;
  /** the batch number (unwrapped) of the batch after the gap, or of the duplicate */
  batch: number;
  /** author µs of the last sample kept before the gap, and of the first sample of this batch */
  from_us: number;
  to_us: number;
  /** index in the capture of the first sample after the gap (= the capture's size for a duplicate) */
  index: number;
  /** the batch numbers restarted (a reboot): `batches` is then the time's estimate, `samples` still counted by time */
  restarted?: boolean;
}

/** Samples lost on the link just before each capture index (the lost gaps, summed where two fall at one index). */
export function lostBeforeIndex(gaps: readonly SampleGap[]): Map<number, number> {
  const lostBefore = new Map<number, number>();
  for (const g of gaps) if (g.kind === 'lost') lostBefore.set(g.index, (lostBefore.get(g.index) ?? 0) + g.samples);
  return lostBefore;
}

const U16 = 0x10000;
const U32 = 0x1_0000_0000;
const RECENT = 63;

/** Keeps the last few values and gives their median. */
class RecentMedian {
  private readonly values: number[] = [];
  push(v: number): void {
    this.values.push(v);
    if (this.values.length > RECENT) this.values.shift();
  }
  get size(): number {
    return this.values.length;
  }
  median(): number {
    if (this.values.length === 0) return NaN;
    const s = [...this.values].sort((a, b) => a - b);
    return s[s.length >> 1];
  }
}

export interface BatchVerdict {
  /** the batch's number, unwrapped (the first batch keeps its wire number) */
  batch: number;
  /** null: the batch follows on; else the gap (a duplicate batch is to be dropped) */
  gap: Omit<SampleGap, 'index'> | null;
}

export class SampleGapDetector {
  private lastSeq: number | null = null;
  private lastBatch = 0;
  private lastSample_us = NaN;
  private lastDevice = NaN;
  private readonly period = new RecentMedian();
  private readonly batchSize = new RecentMedian();

  /**
   * Judges one batch: `seq` its u16 number, `times` its samples' author times (µs, in
   * order) and `deviceTimes` their u32 device stamps. Call `accept` after a batch that
   * was not a duplicate.
   */
  judge(seq: number, times: readonly number[], deviceTimes: readonly number[]): BatchVerdict {
    if (this.lastSeq === null || times.length === 0) return { batch: this.lastSeq === null ? seq : this.lastBatch, gap: null };
    const first = times[0];
    if (!(first > this.lastSample_us)) {
      return {
        batch: this.lastBatch,
        gap: { kind: 'duplicate', batches: 0, samples: 0, droppedSamples: times.length, batch: this.lastBatch, from_us: this.lastSample_us, to_us: first },
      };
    }
    const r = (((seq - this.lastSeq - 1) % U16) + U16) % U16;
    const P = this.period.median();
    const B = this.batchSize.median();
    const bySamples = Number.isFinite(P) && P > 0 ? Math.max(0, Math.round(this.deviceSpan(first, deviceTimes[0]) / P) - 1) : NaN;
    let batches = r;
    if (Number.isFinite(bySamples) && Number.isFinite(B) && B > 0) {
      const k = Math.max(0, Math.round((bySamples / B - r) / U16));
      batches = r + k * U16;
    }
    // Every batch holds a sample at least: more batches missing than samples is impossible,
    // unless the numbering itself restarted (the board rebooted). Then the time decides.
    const restarted = Number.isFinite(bySamples) && batches > bySamples;
    if (restarted) batches = bySamples === 0 ? 0 : Math.max(1, Math.round(bySamples / B));
    const batch = this.lastBatch + batches + 1;
    if (batches === 0) return { batch, gap: null };
    const samples = Math.max(batches, Number.isFinite(bySamples) ? bySamples : batches);
    return { batch, gap: { kind: 'lost', batches, samples, droppedSamples: 0, batch, from_us: this.lastSample_us, to_us: first, restarted } };
  }

  /**
   * Device µs from the last sample kept to a sample at author `t_us` stamped `device`.
   * If that disagrees with the author's clock by more than 1 % (+ 5 ms), the device's
   * clock restarted or jumped (a reboot) and cannot count the gap: the author's span is
   * used instead, still right to the sample for gaps shorter than 50 periods × 1/1 %.
   */
  private deviceSpan(t_us: number, device: number): number {
    const author = t_us - this.lastSample_us;
    const d = (((device - this.lastDevice) % U32) + U32) % U32;
    const span = d + U32 * Math.round((author - d) / U32);
    return Math.abs(span - author) > 0.01 * author + 5000 ? author : span;
  }

  /**
   * Records a kept batch: its wire and unwrapped numbers, its samples' author times, and
   * whether it followed on without a gap (only then does the time across count as a period).
   */
  accept(seq: number, batch: number, times: readonly number[], deviceTimes: readonly number[], followsOn: boolean): void {
    if (times.length === 0) return;
    if (followsOn && !Number.isNaN(this.lastSample_us)) this.period.push(this.deviceSpan(times[0], deviceTimes[0]));
    for (let k = 1; k < times.length; k++) this.period.push((((deviceTimes[k] - deviceTimes[k - 1]) % U32) + U32) % U32);
    this.batchSize.push(times.length);
    this.lastSeq = seq;
    this.lastBatch = batch;
    this.lastSample_us = times[times.length - 1];
    this.lastDevice = deviceTimes[deviceTimes.length - 1];
  }
}
