import { describe, expect, it } from 'vitest';
import fc from 'fast-check';
import { decimate } from './previewDecimation.ts';

/** Distance from p to the segment a→b (3D). */
function toSegment(p: number[], a: number[], b: number[]): number {
  const d = b.map((v, i) => v - a[i]);
  const len2 = d.reduce((s, v) => s + v * v, 0);
  const u = len2 > 0 ? Math.min(1, Math.max(0, p.reduce((s, v, i) => s + (v - a[i]) * d[i], 0) / len2)) : 0;
  return Math.hypot(...p.map((v, i) => v - (a[i] + u * d[i])));
}

const at = (v: Float32Array, i: number) => [v[i * 3], v[i * 3 + 1], v[i * 3 + 2]];

describe('preview decimation (Douglas–Peucker)', () => {
  it('keeps the ends and every dropped vertex within the tolerance of the chord that spans it', () => {
    fc.assert(
      fc.property(
        fc.array(fc.tuple(fc.float({ min: -100, max: 100, noNaN: true }), fc.float({ min: -100, max: 100, noNaN: true })), { minLength: 2, maxLength: 300 }),
        fc.float({ min: Math.fround(0.01), max: 5, noNaN: true }),
        (points, tolerance) => {
          const v = Float32Array.from(points.flatMap(([x, y]) => [x, y, 0]));
          const { vertices, index } = decimate(v, tolerance);
          const n = points.length;
          expect(index[0]).toBe(0);
          expect(index[index.length - 1]).toBe(n - 1);
          expect(vertices.length).toBe(index.length * 3);
          for (let k = 1; k < index.length; k++) {
            expect(index[k]).toBeGreaterThan(index[k - 1]);
            for (let i = index[k - 1] + 1; i < index[k]; i++) {
              expect(toSegment(at(v, i), at(v, index[k - 1]), at(v, index[k]))).toBeLessThanOrEqual(tolerance * (1 + 1e-5) + 1e-6);
            }
          }
          for (let k = 0; k < index.length; k++) expect(at(vertices, k)).toEqual(at(v, index[k]));
        },
      ),
    );
  });

  it('shrinks a fine spiral many times over at a tenth of a millimetre', () => {
    const pts: number[] = [];
    let s = 0;
    for (let i = 0; i < 20_000; i++) {
      const r = 5 + 0.004 * s;
      const a = s / r;
      pts.push(r * Math.cos(a), r * Math.sin(a), 0);
      s += 0.2; // a point every 0.2 mm along the curve
    }
    const { index } = decimate(Float32Array.from(pts), 0.1);
    expect(index.length).toBeLessThan(20_000 / 5);
  });
});
