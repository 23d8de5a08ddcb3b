/**
 * The plot's min/max-per-column decimation against a brute-force reference, on random
 * curves (fast-check): random times, values with unknown (NaN) stretches, lost-sample
 * breaks, any view and any number of columns.
 */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { columnOf, decimateMinMax, type Curve } from './minMaxDecimation.ts';

const curveArb = fc
  .record({
    steps: fc.array(fc.double({ min: 0.001, max: 3, noNaN: true }), { minLength: 0, maxLength: 150, size: 'max' }),
    values: fc.array(fc.oneof({ weight: 9, arbitrary: fc.double({ min: -1e4, max: 1e4, noNaN: true }) }, { weight: 1, arbitrary: fc.constant(NaN) }), { minLength: 150, maxLength: 150 }),
    breakFlags: fc.array(fc.boolean(), { minLength: 150, maxLength: 150 }),
    breakRate: fc.integer({ min: 0, max: 4 }),
  })
  .map(({ steps, values, breakFlags, breakRate }): Curve => {
    const t: number[] = [];
    let x = -5;
    for (const s of steps) t.push((x += s));
    const breaks = t.map((_, k) => k).filter((k) => k > 0 && breakRate > 0 && breakFlags[k] && k % breakRate === 0);
    return { t: Float64Array.from(t), v: Float64Array.from(values.slice(0, t.length)), breaks: Int32Array.from(breaks) };
  });

const viewArb = fc.record({ a: fc.double({ min: -10, max: 400, noNaN: true }), span: fc.double({ min: 0, max: 400, noNaN: true }), columns: fc.integer({ min: 1, max: 60 }) });

/** The last index with t ≤ x, plus one, read one by one. */
function upperBoundRef(t: ArrayLike<number>, x: number): number {
  let k = 0;
  for (let i = 0; i < t.length; i++) if (t[i] <= x) k = i + 1;
  return k;
}

/** The reference: each sample's run (a new one after every break or unknown value) and column, read one by one. */
function reference(curve: Curve, lo: number, hi: number, t0: number, t1: number, columns: number) {
  const breaks = new Set(Array.from(curve.breaks));
  const run: number[] = [];
  let r = 0;
  for (let k = lo; k <= hi; k++) {
    if (breaks.has(k) || !Number.isFinite(curve.v[k])) r++;
    run[k] = Number.isFinite(curve.v[k]) ? r : -1;
  }
  const groups = new Map<string, number[]>();
  for (let k = lo; k <= hi; k++) {
    if (run[k] < 0) continue;
    const key = `${run[k]}/${columnOf(curve.t[k], t0, t1, columns)}`;
    const members = groups.get(key);
    if (members) members.push(k);
    else groups.set(key, [k]);
  }
  return { run, groups, key: (k: number) => `${run[k]}/${columnOf(curve.t[k], t0, t1, columns)}` };
}

describe('min/max decimation', () => {
  it('keeps, per column and unbroken run, exactly the first, lowest, highest and last sample, and breaks where the data does', () => {
    fc.assert(
      fc.property(curveArb, viewArb, (curve, { a, span, columns }) => {
        const t0 = a;
        const t1 = a + span;
        const d = decimateMinMax(curve, t0, t1, columns);
        const n = curve.t.length;
        const inView = Array.from(curve.t).filter((x) => x >= t0 && x <= t1).length;
        expect(d.samplesInView).toBe(inView);
        if (n === 0) {
          expect(d.index.length).toBe(0);
          return;
        }
        // The samples read: those in view and one neighbour each side.
        const firstIn = Array.from(curve.t).findIndex((x) => x >= t0);
        const lastIn = upperBoundRef(curve.t, t1) - 1;
        expect(d.lo).toBe(Math.max(0, (firstIn < 0 ? n : firstIn) - 1));
        expect(d.hi).toBe(Math.min(n - 1, lastIn + 1));
        const ref = reference(curve, d.lo, d.hi, t0, t1, columns);
        const drawn = Array.from(d.index).filter((k) => k >= 0);
        // Real samples, in order, each once, never an unknown value.
        for (let i = 1; i < drawn.length; i++) expect(drawn[i]).toBeGreaterThan(drawn[i - 1]);
        for (const k of drawn) expect(Number.isFinite(curve.v[k])).toBe(true);
        // Per group: first and last kept, min and max exact, at most 4 points.
        const byGroup = new Map<string, number[]>();
        for (const k of drawn) {
          const key = ref.key(k);
          if (byGroup.has(key)) byGroup.get(key)!.push(k);
          else byGroup.set(key, [k]);
        }
        expect([...byGroup.keys()].sort()).toEqual([...ref.groups.keys()].sort());
        for (const [key, members] of ref.groups) {
          const kept = byGroup.get(key)!;
          expect(kept.length).toBeLessThanOrEqual(4);
          expect(kept[0]).toBe(members[0]);
          expect(kept[kept.length - 1]).toBe(members[members.length - 1]);
          expect(Math.min(...kept.map((k) => curve.v[k]))).toBe(Math.min(...members.map((k) => curve.v[k])));
          expect(Math.max(...kept.map((k) => curve.v[k]))).toBe(Math.max(...members.map((k) => curve.v[k])));
        }
        // A break (−1) exactly between drawn samples of different runs; none at either end, never two in a row.
        const idx = Array.from(d.index);
        if (idx.length > 0) {
          expect(idx[0]).not.toBe(-1);
          expect(idx[idx.length - 1]).not.toBe(-1);
        }
        for (let i = 1; i < idx.length; i++) {
          if (idx[i] === -1) {
            expect(idx[i - 1]).not.toBe(-1);
            expect(ref.run[idx[i - 1]]).not.toBe(ref.run[idx[i + 1]]);
          } else if (idx[i - 1] !== -1) {
            expect(ref.run[idx[i - 1]]).toBe(ref.run[idx[i]]);
          }
        }
      }),
      { numRuns: 300 },
    );
  });

  it('draws at most 4 points a column however many samples: 600 000 samples over 700 columns', () => {
    const n = 600_000;
    const t = Float64Array.from({ length: n }, (_, k) => k / 1000);
    const v = Float64Array.from({ length: n }, (_, k) => Math.sin(k * 0.37) * 1000 + (k === 123_456 ? 9000 : 0));
    const d = decimateMinMax({ t, v, breaks: new Int32Array([300_000]) }, 0, t[n - 1], 700);
    expect(d.samplesInView).toBe(n);
    // 4 a column, the one column the break cuts in two holds 8, and the break's marker.
    expect(d.index.length).toBeLessThanOrEqual(4 * 700 + 4 + 1);
    expect(Math.max(...Array.from(d.index).filter((k) => k >= 0).map((k) => v[k]))).toBe(v[123_456]);
    expect(Array.from(d.index).filter((k) => k === -1)).toHaveLength(1);
  });
});
