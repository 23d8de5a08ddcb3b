/**
 * CSV export of a capture (d3-dsv, through csvSafe.ts so no cell reads as a formula):
 * one row per sample received, joined with the plan at its author time.
 *
 *   t_s               seconds from `start_us` (the capture's start: the plot's zero), or from
 *                     the first sample when none is given (author clock)
 *   author_us         the sample's author time, µs: its device stamp through the clock model
 *   device_us         the device's own u32 µs stamp, as it came
 *   batch             the SAMPLES batch it came in (the wire's u16 number, unwrapped)
 *   index_in_batch    its place in that batch
 *   sample_seq        samples the device took before it, lost ones included
 *   lost_before       samples lost just before this one (0 but after a gap); so sample_seq
 *                     rises by exactly 1 + lost_before from row to row
 *   <channels>        the measured values
 *   planned_<a>_mm, planned_v<a>_mm_s, planned_a<a>_mm_s2    per motion axis a
 *   planned_speed_mm_s, planned_path_accel_mm_s2            along the path
 *
 * A lost sample is never interpolated or joined over: its row is absent, and the next
 * row says how many went missing.
 */
import type { TrajectorySample } from '../trajectory/tracks.ts';
import { formatSafeCsvLines, type CsvCell } from './csvSafe.ts';
import { lostBeforeIndex, type SampleGap } from './sampleGaps.ts';

/** A capture's columns (a SensorCapture, or a saved copy of one). */
export interface CaptureColumns {
  readonly reader: string;
  readonly channels: number;
  readonly gaps: readonly SampleGap[];
  timeColumn(): ArrayLike<number>;
  deviceTimeColumn(): ArrayLike<number>;
  batchColumn(): ArrayLike<number>;
  indexColumn(): ArrayLike<number>;
  sequenceColumn(): ArrayLike<number>;
  channel(c: number): ArrayLike<number>;
}

export interface CsvOptions {
  /**
   * The trajectory at sample k's author time t_us; null where the plan is not known
   * (before the as-planned history's horizon): those cells are left empty, never guessed.
   */
  sample(t_us: number, k: number): TrajectorySample | null;
  motionAxes: readonly string[];
  /** names of the capture's channels, e.g. ['ax', 'ay', 'az'] (default: reader name and index) */
  channelNames?: readonly string[];
  /** Author µs that t_s counts from: the capture's start, so that t_s is the time its plot shows (default: the first sample's). */
  start_us?: number;
}

/** The CSV's column names, in order. */
export function captureCsvColumns(capture: Pick<CaptureColumns, 'reader' | 'channels'>, options: Omit<CsvOptions, 'sample'>): string[] {
  return [
    't_s',
    'author_us',
    'device_us',
    'batch',
    'index_in_batch',
    'sample_seq',
    'lost_before',
    ...channelNamesOf(capture, options.channelNames),
    ...options.motionAxes.flatMap((a) => [`planned_${a}_mm`, `planned_v${a}_mm_s`, `planned_a${a}_mm_s2`]),
    'planned_speed_mm_s',
    'planned_path_accel_mm_s2',
  ];
}

function channelNamesOf(capture: Pick<CaptureColumns, 'reader' | 'channels'>, names?: readonly string[]): string[] {
  if (names && names.length !== capture.channels) throw new RangeError(`the capture has ${capture.channels} channels but ${names.length} names were given`);
  return names ? [...names] : Array.from({ length: capture.channels }, (_, c) => `${capture.reader}${c}`);
}

/** Rows per chunk of captureCsvChunks by default: a few milliseconds of work each. */
export const CSV_ROWS_PER_CHUNK = 250;

/**
 * The CSV in pieces, to write a long capture (600 000 rows) without holding the page:
 * the header line, then `rowsPerChunk` rows at a time, each piece after the first
 * beginning with its line break. Joined, they are exactly captureToCsv's text.
 */
export function* captureCsvChunks(capture: CaptureColumns, options: CsvOptions, rowsPerChunk = CSV_ROWS_PER_CHUNK): Generator<string, void, void> {
  if (!(rowsPerChunk >= 1)) throw new RangeError(`rows per chunk must be at least 1 (got ${rowsPerChunk})`);
  const times = capture.timeColumn();
  const device = capture.deviceTimeColumn();
  const batch = capture.batchColumn();
  const index = capture.indexColumn();
  const seq = capture.sequenceColumn();
  const channels = Array.from({ length: capture.channels }, (_, c) => capture.channel(c));
  const lostBefore = lostBeforeIndex(capture.gaps);
  const t0 = options.start_us ?? (times.length > 0 ? times[0] : 0);
  yield formatSafeCsvLines([captureCsvColumns(capture, options)]);
  for (let from = 0; from < times.length; from += rowsPerChunk) {
    const rows: CsvCell[][] = [];
    for (let k = from; k < Math.min(times.length, from + rowsPerChunk); k++) {
      const t = times[k];
      const plan = options.sample(t, k);
      const row: CsvCell[] = [(t - t0) / 1e6, t, device[k], batch[k], index[k], seq[k], lostBefore.get(k) ?? 0];
      for (const values of channels) row.push(values[k]);
      for (let i = 0; i < options.motionAxes.length; i++) row.push(plan?.position[i], plan?.velocity[i], plan?.acceleration[i]);
      row.push(plan?.speed, plan?.pathAcceleration);
      rows.push(row);
    }
    yield `\n${formatSafeCsvLines(rows)}`;
  }
}

export function captureToCsv(capture: CaptureColumns, options: CsvOptions): string {
  return [...captureCsvChunks(capture, options)].join('');
}
