/**
 * Capture CSV: its columns, a lost sample shown and never joined over, and every cell
 * that a spreadsheet could read as a formula neutralised, negative numbers kept numeric.
 */
import { csvParseRows } from 'd3-dsv';
import { describe, expect, it } from 'vitest';
import { ClockMap } from '../net/clockMap.ts';
import { restingSample } from '../trajectory/tracks.ts';
import { captureCsvChunks, captureCsvColumns, captureToCsv } from './csv.ts';
import { formatSafeCsv, safeCell } from './csvSafe.ts';
import { SensorCapture } from './sensorCapture.ts';
import { queueOf } from '../maxl.ts';

const clock = new ClockMap(0, 0, 1);

/** Batches of 2 samples, 10 ms apart, values = −(sample number + 1), all negative. */
function captureWithGap(reader = 'accel'): SensorCapture {
  const capture = new SensorCapture('imu', reader, 2);
  for (const n of [0, 1, 2, 5, 6]) {
    const first = 2 * n;
    capture.add(
      { type: 'SAMPLES', reader: 0, sampleSeq: n, count: 2, t0: 1000 + first * 10_000, samples: [0, 1].map((k) => ({ dt: k * 10_000, values: [-(first + k) - 1, 0.5] })) },
      clock,
      first * 10_000,
    );
  }
  return capture;
}

/** A fake plan: x = t (s), v = 1, a = −2, so the planned columns can be checked. */
const plan = (t_us: number) => ({ ...restingSample([t_us / 1e6], []), velocity: [1], acceleration: [-2], speed: 1, pathAcceleration: -2 });

describe('capture CSV', () => {
  it('has one row per sample with the documented columns, and shows the gap', () => {
    const capture = captureWithGap();
    const rows = csvParseRows(captureToCsv(capture, { sample: plan, motionAxes: ['x'], channelNames: ['ax', 'ay'] }));
    expect(rows[0]).toEqual([
      't_s',
      'author_us',
      'device_us',
      'batch',
      'index_in_batch',
      'sample_seq',
      'lost_before',
      'ax',
      'ay',
      'planned_x_mm',
      'planned_vx_mm_s',
      'planned_ax_mm_s2',
      'planned_speed_mm_s',
      'planned_path_accel_mm_s2',
    ]);
    const data = rows.slice(1).map((r) => r.map(Number));
    expect(data).toHaveLength(10);
    expect(data.map((r) => r[3])).toEqual([0, 0, 1, 1, 2, 2, 5, 5, 6, 6]);
    expect(data.map((r) => r[4])).toEqual([0, 1, 0, 1, 0, 1, 0, 1, 0, 1]);
    expect(data.map((r) => r[5])).toEqual([0, 1, 2, 3, 4, 5, 10, 11, 12, 13]);
    expect(data.map((r) => r[6])).toEqual([0, 0, 0, 0, 0, 0, 4, 0, 0, 0]);
    // The sample number rises by 1 + lost_before, row to row.
    for (let k = 1; k < data.length; k++) expect(data[k][5] - data[k - 1][5]).toBe(1 + data[k][6]);
    for (const r of data) {
      expect(r[7]).toBe(-r[5] - 1); // the measured value: negative, numeric
      expect(r[2]).toBe(1000 + r[5] * 10_000); // the device stamp kept
      expect(r[1]).toBe(r[2]); // identity clock
      expect(r[9]).toBeCloseTo(r[1] / 1e6, 12);
      expect(r.slice(10)).toEqual([1, -2, 1, -2]);
    }
  });

  it('counts t_s from start_us when given (the capture\'s start), else from the first sample', () => {
    const capture = captureWithGap();
    const column = (start_us?: number) => csvParseRows(captureToCsv(capture, { sample: plan, motionAxes: ['x'], start_us })).slice(1).map((r) => [Number(r[0]), Number(r[1])]);
    for (const [t_s, author_us] of column()) expect(t_s).toBeCloseTo((author_us - 1000) / 1e6, 12);
    for (const [t_s, author_us] of column(-500)) expect(t_s).toBeCloseTo((author_us + 500) / 1e6, 12);
  });

  it('neutralises channel and reader names that could be read as formulas', () => {
    const hostile = ['=HYPERLINK("http://x","y")', '+1+2'];
    const capture = captureWithGap('-2+3');
    const text = captureToCsv(capture, { sample: plan, motionAxes: ['x'], channelNames: hostile });
    const header = csvParseRows(text)[0];
    expect(header[7]).toBe(`'${hostile[0]}`);
    expect(header[8]).toBe(`'${hostile[1]}`);
    // Default channel names carry the reader's name.
    expect(captureCsvColumns(capture, { motionAxes: ['x'] }).slice(7, 9)).toEqual(['-2+30', '-2+31']);
    const defaults = csvParseRows(captureToCsv(capture, { sample: plan, motionAxes: ['x'] }))[0];
    expect(defaults.slice(7, 9)).toEqual(["'-2+30", "'-2+31"]);
    // Numbers in the data stay numbers, negative ones too.
    expect(csvParseRows(text)[1][7]).toBe('-1');
    expect(csvParseRows(text)[2][7]).toBe('-2');
  });

  it('safeCell: OWASP triggers get an apostrophe, plain numbers and other text do not', () => {
    for (const bad of ['=1+1', '+1+1', '-1+1', '@SUM(A1)', '\t=1', '\r=1', '-', '+', '=', '-cmd|calc']) expect(safeCell(bad)).toBe(`'${bad}`);
    for (const ok of ['-12.5', '+3', '-1e-3', '.5', '12', 'accel', 'a=b', '', "'=1"]) expect(safeCell(ok)).toBe(ok);
    expect(safeCell(-12.5)).toBe(-12.5);
    expect(safeCell(null)).toBeNull();
    // Quoting of separators, quotes and line breaks stays d3-dsv's.
    expect(formatSafeCsv(['a,b', 'c"d', '=e\nf'], [[-1, 'x'], [null, '@y']])).toBe('"a,b","c""d","\'=e\nf"\n-1,x\n,\'@y');
  });

  it('in chunks: the header, then rows a chunk at a time, joined exactly the whole text, whatever the chunk size', () => {
    const capture = captureWithGap('=reader');
    const options = { sample: (t: number, k: number) => (k === 2 ? null : plan(t)), motionAxes: ['x'] };
    const whole = captureToCsv(capture, options);
    const lines = whole.split('\n');
    expect(lines).toHaveLength(11);
    for (const size of [1, 3, 10, 250]) {
      const chunks = [...captureCsvChunks(capture, options, size)];
      expect(chunks).toHaveLength(1 + Math.ceil(10 / size));
      expect(chunks[0]).toBe(lines[0]);
      expect(chunks.join('')).toBe(whole);
      for (const c of chunks.slice(1)) expect(c.startsWith('\n')).toBe(true);
      // Each row in one piece: the chunk's lines are the whole text's lines in order.
      expect(chunks.slice(1).flatMap((c) => c.slice(1).split('\n'))).toEqual(lines.slice(1));
    }
    expect(() => [...captureCsvChunks(capture, options, 0)]).toThrow(/at least 1/);
  });

  it('refuses a channel name list of the wrong length', () => {
    expect(() => captureToCsv(captureWithGap(), { sample: plan, motionAxes: ['x'], channelNames: ['only one'] })).toThrow(/2 channels but 1 names/);
  });
});

describe('the plan horizon', () => {
  it('the history says where its plan begins once it dropped records, and the CSV leaves those cells empty', async () => {
    const { createMAXL } = await import('../index.ts');
    const maxl = createMAXL({ motionAxes: ['x'], limits: { maxVelocity: 100, maxAcceleration: 1000, junctionDeviation: 0.05 } }, { historyLimit: 3 });
    const q = queueOf(maxl);
    for (const x of [10, 0, 10, 0, 10]) q.append({ endPosition: [x] });
    const sent = [];
    for (let k = 0; k < 3; k++) sent.push(q.transmitNext(0)!);
    expect(maxl.history.horizon_us).toBe(-Infinity);
    sent.push(q.transmitNext(0)!, q.transmitNext(0)!);
    expect(maxl.history.horizon_us).toBe(sent[2].startTime_us);
    expect(maxl.history.pushed).toBe(5);
    const rows = csvParseRows(captureToCsv(captureWithGap(), { sample: (t, k) => (k < 3 ? null : plan(t)), motionAxes: ['x'] }));
    expect(rows[1].slice(9)).toEqual(['', '', '', '', '']);
    expect(rows[4].slice(9).every((c) => c !== '')).toBe(true);
  });
});
