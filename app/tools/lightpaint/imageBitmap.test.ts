import { describe, expect, it } from 'vitest';
import { imageBitmap, scaledLuminance, floydSteinberg, type ImageToBitmapOptions } from './imageBitmap.ts';

/** A w × h RGBA gradient with some transparency, as a decoded photo would give. */
function gradient(w: number, h: number): Uint8ClampedArray {
  const rgba = new Uint8ClampedArray(w * h * 4);
  for (let y = 0; y < h; y++) {
    for (let x = 0; x < w; x++) {
      const p = 4 * (y * w + x);
      rgba[p] = (255 * x) / w;
      rgba[p + 1] = (255 * y) / h;
      rgba[p + 2] = (37 * x + 11 * y) % 256;
      rgba[p + 3] = x % 7 === 0 ? 128 : 255;
    }
  }
  return rgba;
}

/** The same pixels behind a proxy that counts reads of them. */
function counted(rgba: Uint8ClampedArray): { pixels: Uint8ClampedArray; reads: () => number } {
  let reads = 0;
  const pixels = new Proxy(rgba, {
    get(target, key) {
      if (typeof key === 'string' && /^\d+$/.test(key)) reads++;
      const v = Reflect.get(target, key, target);
      return typeof v === 'function' ? v.bind(target) : v;
    },
  });
  return { pixels, reads: () => reads };
}

const options: ImageToBitmapOptions = { height: 8, ledSpacing_mm: 6.4, pitch_mm: 2, halftone: 'threshold', threshold: 0.5 };

describe('imageBitmap: a Level or halftone change does not scale the photo again', () => {
  it('reads the pixels once for a run of thresholds and halftones at one size, and again for a new size', () => {
    const rgba = gradient(120, 40);
    const { pixels, reads } = counted(rgba);
    imageBitmap(pixels, 120, 40, options);
    const first = reads();
    expect(first).toBeGreaterThan(0);
    for (const threshold of [0.2, 0.4, 0.6, 0.8]) for (const halftone of ['threshold', 'dither'] as const) imageBitmap(pixels, 120, 40, { ...options, threshold, halftone });
    expect(reads()).toBe(first);
    imageBitmap(pixels, 120, 40, { ...options, pitch_mm: 1 });
    expect(reads()).toBeGreaterThan(first);
  });

  it('gives exactly the bitmap made from freshly scaled grey levels, for every threshold and halftone, after any order of sizes', () => {
    const rgba = gradient(97, 31);
    for (const pitch_mm of [2, 1.5, 2, 3]) {
      const cols = Math.max(1, Math.round(((97 / 31) * 8 * 6.4) / pitch_mm));
      const grey = scaledLuminance(rgba, 97, 31, cols, 8);
      for (const threshold of [0.25, 0.5, 0.75]) {
        const thresholded = imageBitmap(rgba, 97, 31, { ...options, pitch_mm, threshold });
        expect(Array.from(thresholded.lit)).toEqual(Array.from(grey, (g) => (g >= threshold ? 1 : 0)));
        const dithered = imageBitmap(rgba, 97, 31, { ...options, pitch_mm, threshold, halftone: 'dither' });
        expect(Array.from(dithered.lit)).toEqual(Array.from(floydSteinberg(grey, cols, 8, threshold)));
      }
    }
  });
});
