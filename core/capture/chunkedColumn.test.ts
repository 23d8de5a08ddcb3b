/**
 * The chunked column: what goes in comes out, in order, across chunk boundaries, by
 * index, by range and whole; whole reads are one copy until the next push; bad
 * indices and ranges are refused with what was asked.
 */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { CHUNK, ChunkedColumn } from './chunkedColumn.ts';

/** The first index where a and b differ, or −1 when they are equal (length included). */
function firstDifference(a: Float64Array, b: Float64Array): number {
  if (a.length !== b.length) return Math.min(a.length, b.length);
  for (let k = 0; k < a.length; k++) if (!Object.is(a[k], b[k])) return k;
  return -1;
}

function filled(n: number): ChunkedColumn {
  const c = new ChunkedColumn();
  for (let k = 0; k < n; k++) c.push(k * 0.5 - 3);
  return c;
}

describe('ChunkedColumn', () => {
  it('keeps every value across chunk boundaries: by index, by any range, and whole', () => {
    const n = 2 * CHUNK + 123;
    const c = filled(n);
    expect(c.length).toBe(n);
    const reference = Float64Array.from({ length: n }, (_, k) => k * 0.5 - 3);
    expect(firstDifference(c.toArray(), reference)).toBe(-1);
    for (const k of [0, CHUNK - 1, CHUNK, 2 * CHUNK, n - 1]) expect(c.get(k)).toBe(reference[k]);
    fc.assert(
      fc.property(fc.integer({ min: 0, max: n }), fc.integer({ min: 0, max: n }), fc.integer({ min: 0, max: 5 }), (a, b, at) => {
        const [from, to] = a <= b ? [a, b] : [b, a];
        const out = new Float64Array(to - from + at);
        c.copyInto(out, from, to, at);
        expect(firstDifference(out.subarray(at), reference.subarray(from, to))).toBe(-1);
      }),
      { numRuns: 200 },
    );
  });

  it('a whole read is one copy, the same until the next push', () => {
    const c = filled(10);
    const first = c.toArray();
    expect(c.toArray()).toBe(first);
    c.push(99);
    const second = c.toArray();
    expect(second).not.toBe(first);
    expect(second).toHaveLength(11);
    expect(first).toHaveLength(10);
    expect(second[10]).toBe(99);
    expect(new ChunkedColumn().toArray()).toHaveLength(0);
  });

  it('refuses an index or a range outside it, naming both', () => {
    const c = filled(5);
    expect(() => c.get(5)).toThrow(/index 5 is outside the column \(it holds 5\)/);
    expect(() => c.get(-1)).toThrow(RangeError);
    expect(() => c.copyInto(new Float64Array(10), 2, 6)).toThrow(/range \[2, 6\) is outside the column \(it holds 5\)/);
    expect(() => c.copyInto(new Float64Array(10), 3, 2)).toThrow(RangeError);
  });
});
