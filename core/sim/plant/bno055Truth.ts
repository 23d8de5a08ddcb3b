/**
 * Ground truth for stamped accelerometer samples: which of the simulated BNO055's own
 * samples each captured reading is, and how far its author-time stamp lies from the
 * instant that sample represents.
 *
 * The chip model (bno055.ts) makes sample n as the mean specific force over
 * [n·P − P, n·P] (P its output period) and, with recordSamples, records each one it
 * makes (on a read). The instant a reading represents is the centre of that window,
 * n·P − P/2. A captured reading (mm/s², as the Accelerometer example converts: the
 * register's int16 at 1 m/s² = 100 LSB, × 10) is matched to the chip's samples in
 * order, by its three values to the LSB.
 *
 * Samples lost on the link were still read from the chip, one record each: after a gap
 * of n lost samples the match skips n records before it looks. Matching by value alone
 * took, after a gap, the first record with the same three values, which at 1 kHz on a
 * slow sweep (x changes by a few LSB a sample, y and z barely) can be one of the lost
 * samples: bench capture's ten-minute run matched one sample to a record 3 reads early
 * and called its stamp 3.12 ms off; skipping the gap it is 0.12 ms off.
 */
import type { Bno055 } from './bno055.ts';

const STANDARD_GRAVITY = 9.80665;

export interface StampTruth {
  matched: number;
  unmatched: number;
  /** the chip's samples (one per read by the board) from the one matched first to the one matched last */
  chipSamples: number;
  /** worst |stamp − window centre|, µs, and the mean signed error */
  worst_us: number;
  mean_us: number;
}

/**
 * Compares captured samples `from` … `to − 1` (author µs `times`, x/y/z mm/s² `channels`)
 * with the chip's record.
 */
export function stampTruth(
  chip: Bno055,
  times: ArrayLike<number>,
  channels: ReadonlyArray<ArrayLike<number>>,
  from = 0,
  to = times.length,
  /** samples lost on the link just before each capture index (the capture's gaps) */
  lostBefore: ReadonlyMap<number, number> = new Map(),
): StampTruth {
  const P = chip.samplePeriod_us;
  const taken = chip.samplesTaken;
  const range = chip.range_g * STANDARD_GRAVITY;
  const lsb = (v: number) => Math.round(Math.max(-range, Math.min(range, v)) * 100) * 10;
  // The chip's first sample that could be the first captured: 20 ms before its stamp (the
  // search below looks 50 recorded samples on: one is recorded per read, so 20 ms hold
  // 2 of them at 100 Hz and 20 at 1 kHz).
  let j = 0;
  if (from < to) while (j < taken.length && taken[j].t_us < times[from] - 20_000) j++;
  let matched = 0;
  let unmatched = 0;
  let firstFound = -1;
  let lastFound = -1;
  let worst = 0;
  let sum = 0;
  for (let k = from; k < Math.min(to, times.length); k++) {
    if (firstFound >= 0) j += lostBefore.get(k) ?? 0;
    let found = -1;
    for (let s = j; s < Math.min(taken.length, j + 50); s++) {
      const a = taken[s].accel;
      if (lsb(a[0]) === channels[0][k] && lsb(a[1]) === channels[1][k] && lsb(a[2]) === channels[2][k]) {
        found = s;
        break;
      }
    }
    if (found < 0) {
      unmatched++;
      continue;
    }
    j = found + 1;
    if (firstFound < 0) firstFound = found;
    lastFound = found;
    const error = times[k] - (taken[found].t_us - P / 2);
    worst = Math.max(worst, Math.abs(error));
    sum += error;
    matched++;
  }
  return { matched, unmatched, chipSamples: firstFound < 0 ? 0 : lastFound - firstFound + 1, worst_us: worst, mean_us: matched > 0 ? sum / matched : NaN };
}

/**
 * The peak of the tool's response to the carriage on a belt spring x'' = ω²(u − x) − 2ζωx'
 * (springResponse.ts): H(s) = ω²/(s² + 2ζωs + ω²) from carriage to tool acceleration,
 * |H(jΩ)|² = ω⁴/((ω² − Ω²)² + (2ζωΩ)²), greatest where d/dΩ = 0: Ω_r = ω·√(1 − 2ζ²).
 */
export function resonancePeak_hz(naturalFrequency_hz: number, damping: number): number {
  return naturalFrequency_hz * Math.sqrt(1 - 2 * damping * damping);
}
