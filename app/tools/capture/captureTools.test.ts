/**
 * The capture tool's pure parts: the test motions' arithmetic and refusals, the plot's
 * curves (a break at every gap), peak-keeping decimation, and a record's CSV.
 */
import { csvParseRows } from 'd3-dsv';
import { describe, expect, it } from 'vitest';
import { planTestMotion, strokeTime, TestMotionError, type MachineLimits } from '../../../core/capture/testMotions.ts';
import { decimateMax } from './decimate.ts';
import { measuredCurve, nearest } from './traces.ts';
import { recordCsv, recordSidecar } from './captureRecord.ts';
import type { CaptureRecord } from './protocol.ts';

const LIMITS: MachineLimits = { motionAxes: ['x'], maxVelocity: 150, maxAcceleration: 3000, min: 0, max: 300 };

describe('test motions', () => {
  it('a sweep: out and back at each frequency, stroke a/(16 f²), acceleration accelPerHz·f, frequency rising at the rate asked', () => {
    const p = planTestMotion({ kind: 'sweep', axis: 'x', fromHz: 10, toHz: 20, hzPerSecond: 2, accelPerHz: 60 }, LIMITS, [100]);
    expect(p.moves.length % 2).toBe(0);
    const first = p.moves[0] as { endPosition: number[]; maxAcceleration: number };
    expect(first.maxAcceleration).toBe(600);
    expect(first.endPosition[0] - 100).toBeCloseTo(600 / (16 * 100), 12);
    expect((p.moves[1] as { endPosition: number[] }).endPosition).toEqual([100]);
    // Each cycle lasts 1/f and the frequency rises by rate × 1/f: the sweep takes (to − from)/rate.
    expect(p.duration_s).toBeGreaterThan(4.9);
    expect(p.duration_s).toBeLessThan(5.2);
    expect(p.band_hz).toEqual([10, 20]);
    // A rest-to-rest triangle over the stroke at a lasts half a period.
    expect(2 * Math.sqrt((600 / 1600) / 600)).toBeCloseTo(1 / 20, 12);
  });

  it('growing strokes step their speed from → to, and fit the stroke inside the soft limits', () => {
    const p = planTestMotion({ kind: 'growing', axis: 'x', grow: 'speed', stroke_mm: 20, from: 20, to: 100, steps: 5 }, LIMITS, [290]);
    expect(p.moves.map((m) => (m as { maxVelocity?: number }).maxVelocity)).toEqual([20, 20, 40, 40, 60, 60, 80, 80, 100, 100]);
    expect((p.moves[0] as { endPosition: number[] }).endPosition).toEqual([270]); // no room above 290: goes down
    expect(strokeTime(20, 100, 3000)).toBeCloseTo(0.2 + 100 / 3000, 12);
    expect(strokeTime(1, 100, 3000)).toBeCloseTo(2 * Math.sqrt(1 / 3000), 12);
  });

  it('refuses what it cannot do, naming the field', () => {
    const bad: Array<[unknown, string]> = [
      [{ kind: 'sweep', axis: 'y', fromHz: 10, toHz: 20, hzPerSecond: 1, accelPerHz: 60 }, 'axis'],
      [{ kind: 'sweep', axis: 'x', fromHz: 20, toHz: 10, hzPerSecond: 1, accelPerHz: 60 }, 'toHz'],
      [{ kind: 'sweep', axis: 'x', fromHz: 10, toHz: 20, hzPerSecond: 0, accelPerHz: 60 }, 'hzPerSecond'],
      [{ kind: 'sweep', axis: 'x', fromHz: 1, toHz: 20, hzPerSecond: 1, accelPerHz: 3000 }, 'accelPerHz'],
      [{ kind: 'growing', axis: 'x', grow: 'speed', stroke_mm: 20, from: 20, to: 500, steps: 5 }, 'to'],
      [{ kind: 'growing', axis: 'x', grow: 'speed', stroke_mm: 400, from: 20, to: 50, steps: 5 }, 'stroke_mm'],
      [{ kind: 'growing', axis: 'x', grow: 'speed', stroke_mm: 20, from: 20, to: 50, steps: 0 }, 'steps'],
    ];
    for (const [motion, field] of bad) {
      let error: unknown;
      try {
        planTestMotion(motion as never, LIMITS, [100]);
      } catch (e) {
        error = e;
      }
      expect(error).toBeInstanceOf(TestMotionError);
      expect((error as TestMotionError).field).toBe(field);
    }
  });
});

/** A record of 6 samples with 2 lost after the third. */
function record(): CaptureRecord {
  const f = (xs: number[]) => Float64Array.from(xs);
  return {
    id: 'r',
    date: '2026-01-01T00:00:00.000Z',
    description: 'test',
    motion: { kind: 'sweep', axis: 'x', fromHz: 10, toHz: 20, hzPerSecond: 1, accelPerHz: 60 },
    machine: 'accelRig',
    config: { motionAxes: ['x'] } as CaptureRecord['config'],
    firmware: [{ device: '=evil', link: 'sim', firmware: '0.1.0' }],
    syncError_us: 5,
    start_us: 1000,
    end_us: 100_000,
    cutShort: null,
    warnings: [],
    axes: ['x'],
    plan: { t_us: f([1000, 2000]), acceleration: [f([0, 1])] },
    segments: [],
    sensors: [
      {
        device: 'imu',
        reader: 'accel',
        channelNames: ['=cmd', 'b'],
        author_us: f([1000, 11000, 21000, 51000, 61000, 71000]),
        device_us: f([1, 2, 3, 6, 7, 8]),
        batch: f([0, 0, 1, 3, 3, 4]),
        index: f([0, 1, 0, 0, 1, 0]),
        seq: f([0, 1, 2, 5, 6, 7]),
        values: [f([-1, -2, -3, -4, -5, -6]), f([1, 2, 3, 4, 5, 6])],
        gaps: [{ kind: 'lost', batches: 1, samples: 2, droppedSamples: 0, batch: 3, from_us: 21000, to_us: 51000, index: 3 }],
        planned: { position: [f([0, 1, 2, 3, 4, 5])], velocity: [f([0, 0, 0, 0, 0, 0])], acceleration: [f([9, 9, 9, 9, 9, 9])], speed: f([0, 0, 0, NaN, 0, 0]), pathAcceleration: f([0, 0, 0, 0, 0, 0]) },
      },
    ],
    analysis: null,
    simulatorTruth: null,
  };
}

describe('plot curves', () => {
  it('break at a gap (listed, never a joined line), and the cursor finds the nearest sample with a value', () => {
    const curve = measuredCurve(record(), 0, 0);
    expect(Array.from(curve.v)).toEqual([-1, -2, -3, -4, -5, -6]);
    expect(Array.from(curve.breaks)).toEqual([3]);
    expect(curve.t[3]).toBeCloseTo(0.05, 12);
    expect(curve.v[nearest(curve, 0.049)]).toBe(-4);
    expect(curve.v[nearest(curve, 0.0)]).toBe(-1);
    expect(curve.v[nearest(curve, 1)]).toBe(-6);
    // Unknown values are skipped: the nearest known one either side.
    const planned = { t: Float64Array.from([0, 1, 2, 3]), v: Float64Array.from([5, NaN, NaN, 7]), breaks: new Int32Array(0) };
    expect(nearest(planned, 1.2)).toBe(0);
    expect(nearest(planned, 1.9)).toBe(3);
    expect(nearest({ t: new Float64Array(0), v: new Float64Array(0), breaks: new Int32Array(0) }, 1)).toBe(-1);
  });

  it('decimation keeps every bucket’s peak', () => {
    const values = Array.from({ length: 1000 }, (_, k) => (k === 537 ? 10 : Math.sin(k)));
    const { x, y } = decimateMax(values, 0.5, 50);
    expect(x).toHaveLength(50);
    expect(Math.max(...y)).toBe(10);
    expect(x[y.indexOf(10)]).toBe(537 * 0.5);
  });
});

describe('record exports', () => {
  it('the CSV has a row per sample, the gap shown, planned cells empty where unknown, names neutralised', () => {
    const rows = csvParseRows(recordCsv(record()));
    expect(rows).toHaveLength(7);
    expect(rows[0].slice(7, 9)).toEqual(["'=cmd", 'b']);
    expect(rows.slice(1).map((r) => r[6])).toEqual(['0', '0', '0', '2', '0', '0']);
    expect(rows[4].slice(9)).toEqual(['', '', '', '', '']);
    expect(rows[1][7]).toBe('-1');
    const side = recordSidecar(record());
    expect(side.samplesLost).toBe(2);
    expect(side.clockSyncError_us).toBe(5);
  });

  it("the CSV's t_s is the time the plot shows: seconds from the capture's start, not from its first sample", () => {
    // The capture started 1.75 ms before its first sample came (as on the simulated rig).
    const r = { ...record(), start_us: 1000 - 1750 };
    const t_s = csvParseRows(recordCsv(r)).slice(1).map((row) => Number(row[0]));
    expect(t_s).toEqual(Array.from(measuredCurve(r, 0, 0).t));
    expect(t_s[0]).toBeCloseTo(0.00175, 12);
  });
});
