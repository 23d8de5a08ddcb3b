/**
 * Placing a drawing: true size centred, quarter turns, fit with a margin, the
 * file's own coordinates from the work origin, and a drawing too large said, not
 * clipped.
 */
import { describe, expect, it } from 'vitest';
import { arrange, DEFAULT_ARRANGEMENT, type Area } from './arrange.ts';
import { boundsOf, pathFromPoints } from './paths.ts';

const bed: Area = { minX: 0, minY: 0, maxX: 125, maxY: 125 };
// An L: 40 mm along x, 10 mm up y, from (100, 200).
const L = [pathFromPoints([100, 210, 100, 200, 140, 200])];

describe('arrange', () => {
  it('true size, centred in the area', () => {
    const p = arrange(L, DEFAULT_ARRANGEMENT, bed, [0, 0]);
    expect(Array.from(p.paths[0].points)).toEqual([42.5, 67.5, 42.5, 57.5, 82.5, 57.5]);
    expect(p.fits).toBe(true);
    expect(p.scale).toBe(1);
  });

  it('quarter turns counter-clockwise about the drawing’s centre', () => {
    const p = arrange(L, { ...DEFAULT_ARRANGEMENT, rotate_deg: 90 }, bed, [0, 0]);
    const b = boundsOf(p.paths)!;
    expect([b.maxX - b.minX, b.maxY - b.minY]).toEqual([10, 40]);
    // The corner (100, 200) is the L's lower-left; a quarter turn puts it at the lower-right.
    expect(p.paths[0].points[2]).toBeCloseTo(b.maxX, 9);
    expect(p.paths[0].points[3]).toBeCloseTo(b.minY, 9);
    const half = arrange(L, { ...DEFAULT_ARRANGEMENT, rotate_deg: 180 }, bed, [0, 0]);
    expect(half.paths[0].points[2]).toBeCloseTo(82.5, 9);
    expect(half.paths[0].points[3]).toBeCloseTo(67.5, 9);
  });

  it('fit: the largest scale inside the area less the margin, centred', () => {
    const p = arrange(L, { ...DEFAULT_ARRANGEMENT, fit: true, margin_mm: 5 }, bed, [0, 0]);
    expect(p.scale).toBeCloseTo(115 / 40, 12);
    const b = boundsOf(p.paths)!;
    expect(b.minX).toBeCloseTo(5, 9);
    expect(b.maxX).toBeCloseTo(120, 9);
    expect((b.minY + b.maxY) / 2).toBeCloseTo(62.5, 9);
    const turned = arrange(L, { ...DEFAULT_ARRANGEMENT, fit: true, rotate_deg: 270, margin_mm: 10 }, bed, [0, 0]);
    const tb = boundsOf(turned.paths)!;
    expect(tb.minY).toBeCloseTo(10, 9);
    expect(tb.maxY).toBeCloseTo(115, 9);
  });

  it('too large: said (fits false) with the scale that would fit, never clipped', () => {
    const big = arrange(L, { ...DEFAULT_ARRANGEMENT, scale: 4 }, bed, [0, 0]);
    expect(big.fits).toBe(false);
    expect(big.fitScale).toBeCloseTo(115 / 40, 12);
    expect(boundsOf(big.paths)!.maxX - boundsOf(big.paths)!.minX).toBeCloseTo(160, 9);
    expect(big.paths[0].points.length).toBe(6);
  });

  it('file placement keeps the file’s coordinates from the work origin', () => {
    const p = arrange([pathFromPoints([1, 2, 3, 4])], { ...DEFAULT_ARRANGEMENT, place: 'file' }, bed, [10, 20]);
    expect(Array.from(p.paths[0].points)).toEqual([11, 22, 13, 24]);
    const outside = arrange(L, { ...DEFAULT_ARRANGEMENT, place: 'file' }, bed, [0, 0]);
    expect(outside.fits).toBe(false);
    expect(arrange(L, DEFAULT_ARRANGEMENT, null, [0, 0]).fits).toBe(null);
  });
});
