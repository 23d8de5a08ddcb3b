/**
 * What the strip writes: a bitmap as tall as the strip has LEDs, one column per
 * pixel pitch along the move. Made from typed text (font5x7.ts), painted by
 * hand, or from an image (imageBitmap.ts).
 *
 * Row 0 is the top of the picture, drawn by the strip's last LED (the one at
 * the largest y); the bottom row is LED 0. A column's event value has bit i set
 * when LED i is lit (the paper's 8-bit track, one bit per LED).
 */
import { GLYPH_HEIGHT, GLYPH_WIDTH, LETTER_SPACING, glyphRows, hasGlyph } from './font5x7.ts';

export interface Bitmap {
  width: number;
  height: number;
  /** 1 lit, 0 dark; row-major, row 0 at the top. */
  lit: Uint8Array;
}

/** A bad input, said in words a user can act on. */
export class BitmapError extends Error {}

export function emptyBitmap(width: number, height: number): Bitmap {
  return { width, height, lit: new Uint8Array(width * height) };
}

export function isLit(b: Bitmap, row: number, col: number): boolean {
  return b.lit[row * b.width + col] === 1;
}

/**
 * Typed text in the 5 × 7 font, one dark column between letters. On a strip of
 * 14 LEDs or more the letters are drawn `floor(height / 7)` times larger. A
 * letter the font lacks is drawn as LED signs draw it, from letters it has: its
 * capitals (ß as SS), or without its accents (É as E, ñ as N).
 * Throws a BitmapError for empty text, a strip shorter than 7 LEDs, or
 * characters the font cannot draw so (naming them).
 */
export function textBitmap(text: string, height: number): Bitmap {
  const typed = Array.from(text.replace(/\s+/g, ' ').trim());
  if (typed.length === 0) throw new BitmapError('Type some text to paint.');
  if (height < GLYPH_HEIGHT) throw new BitmapError(`The strip has ${height} LEDs; text needs at least ${GLYPH_HEIGHT}.`);
  const missing = [...new Set(typed.filter((c) => drawnAs(c) === null))];
  if (missing.length > 0) throw new BitmapError(`The font has no ${missing.map((c) => `“${c}”`).join(', ')}: use letters, digits and common punctuation.`);
  const chars = typed.flatMap((c) => drawnAs(c) as string[]);
  const scale = Math.floor(height / GLYPH_HEIGHT);
  const advance = (GLYPH_WIDTH + LETTER_SPACING) * scale;
  const width = chars.length * advance - LETTER_SPACING * scale;
  const out = emptyBitmap(width, height);
  chars.forEach((ch, k) => {
    const rows = glyphRows(ch) as boolean[][];
    for (let r = 0; r < GLYPH_HEIGHT * scale; r++) {
      for (let c = 0; c < GLYPH_WIDTH * scale; c++) {
        if (rows[Math.floor(r / scale)][Math.floor(c / scale)]) out.lit[r * width + k * advance + c] = 1;
      }
    }
  });
  return out;
}

/** The font's characters that draw `ch`: itself, its capitals, or itself without accents; null if none does. */
function drawnAs(ch: string): string[] | null {
  if (hasGlyph(ch)) return [ch];
  const capitals = Array.from(ch.toUpperCase());
  if (capitals.length > 1 && capitals.every(hasGlyph)) return capitals;
  const bare = Array.from(ch.normalize('NFD').replace(/\p{M}+/gu, ''));
  if (bare.length > 0 && bare.join('') !== ch && bare.every(hasGlyph)) return bare;
  return null;
}

/** The bitmap `times` times side by side. */
export function repeatBitmap(b: Bitmap, times: number): Bitmap {
  if (times <= 1) return b;
  const out = emptyBitmap(b.width * times, b.height);
  for (let r = 0; r < b.height; r++) {
    for (let k = 0; k < times; k++) out.lit.set(b.lit.subarray(r * b.width, (r + 1) * b.width), r * out.width + k * b.width);
  }
  return out;
}

/** Each column's event value: bit i lit for LED i, LED 0 drawing the bottom row. */
export function columnBits(b: Bitmap): number[] {
  const bits = new Array<number>(b.width).fill(0);
  for (let c = 0; c < b.width; c++) {
    for (let r = 0; r < b.height; r++) if (b.lit[r * b.width + c]) bits[c] |= 1 << (b.height - 1 - r);
  }
  return bits;
}

/** Whether any pixel is lit. */
export function anyLit(b: Bitmap): boolean {
  return b.lit.some((v) => v === 1);
}
