/**
 * The exposure analysis on synthetic exposures with a known answer: a bitmap
 * drawn shifted by a known amount reads back that shift; a missing column is
 * reported; an uneven bar reads back its unevenness.
 */
import { describe, expect, it } from 'vitest';
import { analyseColumns, exposureEvenness, type ExposureChannel } from './exposureAnalysis.ts';
import { exposureFrame, fullScaleFor, linearToSrgb, srgbToLinear } from './exposureFrame.ts';
import { ledColour } from './ledColour.ts';
import type { RasterLayout } from './raster.ts';

const MM_PER_PX = 0.5;
const OFFSETS = [-3, 3];

/** Draws each lit (column, LED) as light on [x0 + c·p + shift, x0 + (c+1)·p + shift), `perMm(x)` per mm, integrated exactly per pixel. */
function draw(layout: RasterLayout, shift: number, perMm: (x: number) => number = () => 1, skip?: { column: number; led: number }): ExposureChannel {
  const width = 200;
  const height = 40;
  const origin: [number, number] = [0, -10];
  const values = new Float64Array(width * height);
  layout.bits.forEach((bits, c) => {
    OFFSETS.forEach((offset, led) => {
      if (!((bits >> led) & 1) || (skip && skip.column === c && skip.led === led)) return;
      const j = Math.round((layout.y + offset - origin[1]) / MM_PER_PX);
      const a = layout.x0 + c * layout.pitch_mm + shift;
      const b = a + layout.pitch_mm;
      // Each pixel i holds the light within ±½ pixel of its centre (box), in 0.01 mm steps.
      for (let x = a + 0.005; x < b; x += 0.01) {
        const i = Math.round((x - origin[0]) / MM_PER_PX);
        values[j * width + i] += perMm(x) * 0.01;
      }
    });
  });
  return { width, height, mmPerPixel: MM_PER_PX, origin_mm: origin, values };
}

const layout: RasterLayout = { x0: 20, pitch_mm: 2, bits: [0b01, 0b11, 0b00, 0b10, 0b11, 0b11, 0b00, 0b01], y: 0, xStart: 19, xEnd: 38 };

describe('exposure analysis', () => {
  it('reads a drawing in place as in place, and a shifted one as shifted by that much', () => {
    const exact = analyseColumns(draw(layout, 0), layout, OFFSETS);
    expect(exact.mismatches).toEqual([]);
    expect(exact.placementError_mm).toBeLessThan(0.01);
    expect(exact.edgeError_mm).toBeLessThan(0.26);
    for (const shift of [0.3, -0.45]) {
      const a = analyseColumns(draw(layout, shift), layout, OFFSETS);
      expect(a.mismatches).toEqual([]);
      expect(a.placementError_mm).toBeCloseTo(Math.abs(shift), 2);
      for (const run of a.runs) expect(run.centroidError_mm).toBeCloseTo(shift, 2);
    }
  });

  it('reports a column that stayed dark, and one lit by a shift of a whole pitch', () => {
    const missing = analyseColumns(draw(layout, 0, undefined, { column: 4, led: 0 }), layout, OFFSETS);
    expect(missing.mismatches).toEqual([{ column: 4, led: 0, expected: true, level: 0 }]);
    const shifted = analyseColumns(draw(layout, 2), layout, OFFSETS);
    expect(shifted.mismatches.length).toBeGreaterThan(0);
  });

  it('measures light per mm against cruise on an all-lit bar', () => {
    const bar: RasterLayout = { ...layout, bits: new Array(40).fill(0b11), xEnd: 101 };
    // Cruise from x = 40.25 mm on (a pixel's edge: bins are whole pixels); 15 % short of
    // light where the "speed" is below cruise.
    const speedAt = (x: number) => (x < 40.25 ? 50 : 100);
    const e = exposureEvenness(draw(bar, 0, (x) => (x < 40.25 ? 0.85 : 1)), bar, OFFSETS, speedAt, 100);
    expect(e.cruiseSpread).toBeLessThan(1e-6);
    expect(e.rampSpread).toBeCloseTo(0.15, 4);
    expect(e.rampBins).toBe(20);
  });
});

describe('exposure frame', () => {
  it('turns y up (row 0 is the largest y) and shows full scale as 255', () => {
    // 2 × 2 pixels, j grows with y: the pixel at (0, 1) is red at full scale.
    const image = new Float32Array(2 * 2 * 3);
    image[3 * (1 * 2 + 0)] = 0.5;
    const f = exposureFrame(image, 2, 2, 0.5, [0, 0], 0.5);
    expect(Array.from(f.rgba.subarray(0, 4))).toEqual([255, 0, 0, 255]);
    expect(Array.from(f.rgba.subarray(8, 12))).toEqual([0, 0, 0, 255]);
  });

  it('shows the colour picked: the PWM values (linear light) are encoded in sRGB, as a camera writes them', () => {
    // #ffa040 at gamma 2.2 lights the LED at PWM (255, 91, 12). Shown as those bytes, the
    // photo was red-orange, not the orange picked; sRGB-encoded it is (255, 161, 61): within
    // 4 of the pick (the 8-bit PWM's step at 12 and γ 2.2 against sRGB's curve).
    const picked = [0xff, 0xa0, 0x40] as const;
    const pwm = ledColour(picked, 1, 2.2);
    expect(pwm).toEqual([255, 91, 12]);
    const fullScale = fullScaleFor(pwm, 0.5, 100);
    // A lit LED passing at cruise leaves pwm · px / v on its row.
    const image = Float32Array.from(pwm.map((c) => (c * 0.5) / 100));
    const f = exposureFrame(image, 1, 1, 0.5, [0, 0], fullScale);
    for (let c = 0; c < 3; c++) expect(Math.abs(f.rgba[c] - picked[c])).toBeLessThanOrEqual(4);
    // Half the light is not half the byte: the encoding is sRGB's, and srgbToLinear undoes it.
    const half = exposureFrame(Float32Array.of(0.5 * image[0], 0, 0), 1, 1, 0.5, [0, 0], fullScale);
    expect(half.rgba[0]).toBe(Math.round(255 * linearToSrgb(0.5)));
    expect(srgbToLinear(half.rgba[0] / 255)).toBeCloseTo(0.5, 2);
    for (let k = 0; k <= 255; k++) expect(Math.round(255 * linearToSrgb(srgbToLinear(k / 255)))).toBe(k);
  });
});
