/**
 * The simulator's exposure (linear RGB, 8-bit value × s, j growing with y) as
 * an 8-bit RGBA image seen from above: row 0 at the top (largest y), `fullScale`
 * shown as 255 (more saturates), each channel's light encoded in sRGB as a
 * camera writes its photographs, so the picture shows the colour picked.
 *
 * Full scale: a lit LED at colour c passing at cruise v leaves c·(px / v) on
 * the pixel row it crosses (px = mm per pixel), split between the two nearest
 * rows; with the strip dimmed by v / cruise that holds on the ramps too. So
 * full scale = brightest channel × px / v shows a straight pass at its own
 * colour, a little dimmer where the LED falls between two rows.
 *
 * Colour: the LED's PWM values are linear light, 255 · level^γ of the picked
 * level (ledColour.ts, γ 2.2). Written as bytes unchanged (as this once did),
 * #ffa040 showed as (255, 91, 12), a red-orange; sRGB-encoded, linear light L
 * becomes 255 · (12.92 L) below L = 0.0031308, else 255 · (1.055 L^(1/2.4) − 0.055)
 * (IEC 61966-2-1), and #ffa040 shows as (255, 161, 61). Twice the light is no
 * longer twice the byte: `srgbToLinear` undoes it to measure a saved PNG.
 */
import type { ExposureFrame } from './protocol.ts';

export function fullScaleFor(colour: readonly number[], mmPerPixel: number, speed: number): number {
  return (Math.max(1, ...colour) * mmPerPixel) / speed;
}

/** Linear light 0..1 → sRGB 0..1 (IEC 61966-2-1). */
export function linearToSrgb(l: number): number {
  if (!(l > 0)) return 0;
  if (l >= 1) return 1;
  return l <= 0.0031308 ? 12.92 * l : 1.055 * Math.pow(l, 1 / 2.4) - 0.055;
}

/** sRGB 0..1 → linear light 0..1: the inverse of linearToSrgb. */
export function srgbToLinear(s: number): number {
  if (!(s > 0)) return 0;
  if (s >= 1) return 1;
  return s <= 0.04045 ? s / 12.92 : Math.pow((s + 0.055) / 1.055, 2.4);
}

/** Steps of the encoding table: linear light in 1/4096ths, finer than a byte's darkest sRGB step (1/3295). */
const TABLE_STEPS = 4096;
let table: Uint8Array | null = null;

/** Bytes of linearToSrgb(k / TABLE_STEPS), k = 0 … TABLE_STEPS. */
function encodingTable(): Uint8Array {
  if (!table) {
    table = new Uint8Array(TABLE_STEPS + 1);
    for (let k = 0; k <= TABLE_STEPS; k++) table[k] = Math.round(255 * linearToSrgb(k / TABLE_STEPS));
  }
  return table;
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
  const toSrgb = encodingTable();
  const gain = TABLE_STEPS / fullScale;
  const step = (v: number) => toSrgb[Math.min(TABLE_STEPS, Math.max(0, Math.round(v * gain)))];
  for (let j = 0; j < height; j++) {
    const row = height - 1 - j;
    for (let i = 0; i < width; i++) {
      const s = 3 * (j * width + i);
      const d = 4 * (row * width + i);
      rgba[d] = step(image[s]);
      rgba[d + 1] = step(image[s + 1]);
      rgba[d + 2] = step(image[s + 2]);
      rgba[d + 3] = 255;
    }
  }
  return { width, height, rgba, mmPerPixel, origin_mm: [origin_mm[0], origin_mm[1]], fullScale };
}
