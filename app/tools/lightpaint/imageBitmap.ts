/**
 * An image (decoded on the page: RGBA, 8 bits a channel) made into a strip
 * bitmap: scaled to the strip's height with the picture's aspect kept on the
 * machine, then made one bit a pixel (each LED is on or off), by a threshold
 * or by Floyd–Steinberg error diffusion (Pixelstick's way with photographs).
 *
 * Aspect: a bitmap row is one LED spacing tall (s mm) and a column one pixel
 * pitch wide (p mm), so an image w × h shown `height` LEDs tall is
 * w/h · height · s mm wide, that is w/h · height · s / p columns.
 *
 * Scaling is by area: each bitmap pixel is the mean luminance of the image
 * pixels it covers (fractional overlaps weighted), so a large photo does not
 * alias. Luminance is Rec. 709 on the stored values; transparent pixels count
 * as dark (nothing to light).
 */
import { BitmapError, emptyBitmap, type Bitmap } from './bitmap.ts';

export type Halftone = 'threshold' | 'dither';

export interface ImageToBitmapOptions {
  /** LEDs: the bitmap's height. */
  height: number;
  /** mm between LEDs across the move. */
  ledSpacing_mm: number;
  /** mm between columns along the move. */
  pitch_mm: number;
  halftone: Halftone;
  /** 0..1: lit above this luminance (threshold), or the mid grey of dithering. */
  threshold: number;
}

/** Grey levels 0..1 of an RGBA image scaled to `cols` × `rows` by area. */
export function scaledLuminance(rgba: Uint8ClampedArray | Uint8Array, w: number, h: number, cols: number, rows: number): Float64Array {
  const out = new Float64Array(cols * rows);
  const sx = w / cols;
  const sy = h / rows;
  for (let r = 0; r < rows; r++) {
    const y0 = r * sy;
    const y1 = y0 + sy;
    for (let c = 0; c < cols; c++) {
      const x0 = c * sx;
      const x1 = x0 + sx;
      let sum = 0;
      let area = 0;
      for (let y = Math.floor(y0); y < Math.min(h, Math.ceil(y1)); y++) {
        const wy = Math.min(y + 1, y1) - Math.max(y, y0);
        for (let x = Math.floor(x0); x < Math.min(w, Math.ceil(x1)); x++) {
          const wx = Math.min(x + 1, x1) - Math.max(x, x0);
          const p = 4 * (y * w + x);
          const lum = (0.2126 * rgba[p] + 0.7152 * rgba[p + 1] + 0.0722 * rgba[p + 2]) / 255;
          sum += lum * (rgba[p + 3] / 255) * wx * wy;
          area += wx * wy;
        }
      }
      out[r * cols + c] = area > 0 ? sum / area : 0;
    }
  }
  return out;
}

/**
 * Floyd–Steinberg: each pixel becomes 0 or 1, and its error (grey − chosen)
 * goes on to the unvisited neighbours, 7/16 right, 3/16 below left, 5/16
 * below, 1/16 below right, so the mean light of any area is kept.
 */
export function floydSteinberg(grey: Float64Array, cols: number, rows: number, threshold = 0.5): Uint8Array {
  const g = Float64Array.from(grey);
  const out = new Uint8Array(cols * rows);
  for (let r = 0; r < rows; r++) {
    for (let c = 0; c < cols; c++) {
      const i = r * cols + c;
      const on = g[i] >= threshold ? 1 : 0;
      out[i] = on;
      const err = g[i] - on;
      if (c + 1 < cols) g[i + 1] += (err * 7) / 16;
      if (r + 1 < rows) {
        if (c > 0) g[i + cols - 1] += (err * 3) / 16;
        g[i + cols] += (err * 5) / 16;
        if (c + 1 < cols) g[i + cols + 1] += err / 16;
      }
    }
  }
  return out;
}

/**
 * Each image's grey levels at the last size asked, kept by its pixel array (which
 * the page never changes once decoded). The panel makes the bitmap again at every
 * step of the Level slider and at every change of halftone; scaling is the costly
 * part (every pixel of the photo is read: 130–350 ms a step for a 12 MP photo),
 * and only a new size (the pitch, the strip's height) needs it again.
 */
const scaledCache = new WeakMap<object, { cols: number; rows: number; grey: Float64Array }>();

function scaledLuminanceOf(rgba: Uint8ClampedArray | Uint8Array, w: number, h: number, cols: number, rows: number): Float64Array {
  const kept = scaledCache.get(rgba);
  if (kept && kept.cols === cols && kept.rows === rows) return kept.grey;
  const grey = scaledLuminance(rgba, w, h, cols, rows);
  scaledCache.set(rgba, { cols, rows, grey });
  return grey;
}

export function imageBitmap(rgba: Uint8ClampedArray | Uint8Array, w: number, h: number, o: ImageToBitmapOptions): Bitmap {
  if (!(w > 0 && h > 0) || rgba.length !== w * h * 4) throw new BitmapError(`The image is empty or its pixels do not match its size (${w} × ${h}).`);
  if (!(o.pitch_mm > 0) || !(o.ledSpacing_mm > 0)) throw new BitmapError('The pixel pitch and the LED spacing must be positive.');
  const cols = Math.max(1, Math.round(((w / h) * o.height * o.ledSpacing_mm) / o.pitch_mm));
  // (Read only below: floydSteinberg works on a copy.)
  const grey = scaledLuminanceOf(rgba, w, h, cols, o.height);
  const out = emptyBitmap(cols, o.height);
  if (o.halftone === 'dither') out.lit.set(floydSteinberg(grey, cols, o.height, o.threshold));
  else for (let i = 0; i < grey.length; i++) out.lit[i] = grey[i] >= o.threshold ? 1 : 0;
  return out;
}
