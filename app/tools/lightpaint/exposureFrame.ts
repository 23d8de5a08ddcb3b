/**
 * The simulator's exposure (linear RGB, 8-bit value × s, j growing with y) as
 * an 8-bit RGBA image seen from above: row 0 at the top (largest y), each
 * channel linear in light, `fullScale` shown as 255 (more saturates).
 *
 * Full scale: a lit LED at colour c passing at cruise v leaves c·(px / v) on
 * the pixel row it crosses (px = mm per pixel), split between the two nearest
 * rows; with the strip dimmed by v / cruise that holds on the ramps too. So
 * full scale = brightest channel × px / v shows a straight pass at its own
 * colour, a little dimmer where the LED falls between two rows.
 */
import type { ExposureFrame } from './protocol.ts';

export function fullScaleFor(colour: readonly number[], mmPerPixel: number, speed: number): number {
  return (Math.max(1, ...colour) * mmPerPixel) / speed;
}

export function exposureFrame(
  image: Float32Array,
  width: number,
  height: number,
  mmPerPixel: number,
  origin_mm: readonly [number, number],
  fullScale: number,
): ExposureFrame {
  const rgba = new Uint8ClampedArray(width * height * 4);
  const gain = 255 / fullScale;
  for (let j = 0; j < height; j++) {
    const row = height - 1 - j;
    for (let i = 0; i < width; i++) {
      const s = 3 * (j * width + i);
      const d = 4 * (row * width + i);
      rgba[d] = image[s] * gain;
      rgba[d + 1] = image[s + 1] * gain;
      rgba[d + 2] = image[s + 2] * gain;
      rgba[d + 3] = 255;
    }
  }
  return { width, height, rgba, mmPerPixel, origin_mm: [origin_mm[0], origin_mm[1]], fullScale };
}
