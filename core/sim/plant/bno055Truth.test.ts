import { describe, expect, it } from 'vitest';
import type { Bno055 } from './bno055.ts';
import { stampTruth } from './bno055Truth.ts';

/**
 * The chip's record as stampTruth reads it (period, range, the samples read), for a
 * slow signal at 1 kHz: x steps by one LSB every other read, so equal triples recur.
 */
function record(reads: number) {
  const P = 1000;
  const samplesTaken = Array.from({ length: reads }, (_, n) => ({
    t_us: 10_000 + n * P,
    accel: [Math.floor(n / 2) * 0.01, 0, 9.81] as [number, number, number],
    truth: [0, 0, 0] as [number, number, number],
  }));
  return { samplePeriod_us: P, range_g: 4, samplesTaken } as unknown as Bno055;
}

/** The board's stamps: the window's centre, read − P/2, plus `skew_us`; values as the example converts them (mm/s², LSB × 10). */
function captured(chip: Bno055, indices: number[], skew_us: number) {
  const lsb = (v: number) => Math.round(v * 100) * 10;
  const times = indices.map((n) => chip.samplesTaken[n].t_us - chip.samplePeriod_us / 2 + skew_us);
  const channels = [0, 1, 2].map((c) => indices.map((n) => lsb(chip.samplesTaken[n].accel[c])));
  return { times, channels };
}

describe('stampTruth after samples lost on the link', () => {
  // Reads 0–9 received, 10–12 lost (one batch of 3), 13–19 received. Read 13 has the
  // same values as read 12 (x steps every other read), so by value alone it matched 12.
  const chip = record(20);
  const got = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 13, 14, 15, 16, 17, 18, 19];
  const { times, channels } = captured(chip, got, 100);

  it('skips the lost samples’ records: every stamp 100 µs from its window’s centre', () => {
    const t = stampTruth(chip, times, channels, 0, times.length, new Map([[10, 3]]));
    expect(t.matched).toBe(got.length);
    expect(t.worst_us).toBeCloseTo(100, 6);
    expect(t.chipSamples).toBe(20);
  });

  it('by value alone, the sample after the gap matches a lost one, a sample period early (the bench’s 3.12 ms)', () => {
    const t = stampTruth(chip, times, channels);
    expect(t.worst_us).toBeCloseTo(1100, 6);
  });
});
