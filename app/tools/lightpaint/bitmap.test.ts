import { describe, expect, it } from 'vitest';
import fc from 'fast-check';
import { BitmapError, columnBits, repeatBitmap, textBitmap } from './bitmap.ts';
import { FONT_CHARACTERS, GLYPH_HEIGHT, GLYPH_WIDTH, glyphRows } from './font5x7.ts';
import { floydSteinberg, imageBitmap, scaledLuminance } from './imageBitmap.ts';
import { ledColour, packColour, parseHexColour } from './ledColour.ts';

describe('font', () => {
  it('has 7 rows of 5 columns for every glyph', () => {
    for (const ch of FONT_CHARACTERS) {
      const rows = glyphRows(ch)!;
      expect(rows, ch).toHaveLength(GLYPH_HEIGHT);
      for (const r of rows) expect(r, ch).toHaveLength(GLYPH_WIDTH);
    }
  });
  it('draws lower case as capitals', () => {
    expect(glyphRows('h')).toEqual(glyphRows('H'));
  });
});

describe('textBitmap', () => {
  it('lays letters 5 wide with one dark column between, on 8 rows with the bottom one dark', () => {
    const b = textBitmap('HI', 8);
    expect(b.width).toBe(11);
    expect(b.height).toBe(8);
    const bits = columnBits(b);
    // H's first column: rows 0..6 lit → LEDs 7..1 (LED 0 draws the bottom row).
    expect(bits[0]).toBe(0b11111110);
    // H's middle column: only row 3 → LED 4.
    expect(bits[2]).toBe(1 << 4);
    expect(bits[5]).toBe(0);
    for (const v of bits) expect(v & 1).toBe(0);
  });
  it('refuses empty text, missing glyphs and a strip too short, saying which', () => {
    expect(() => textBitmap('   ', 8)).toThrow(BitmapError);
    expect(() => textBitmap('A€B', 8)).toThrow(/“€”/);
  });

  it('draws a letter the font lacks as LED signs do: without its accents, or in its capitals', () => {
    const same = (typed: string, drawn: string) => expect(Array.from(textBitmap(typed, 8).lit)).toEqual(Array.from(textBitmap(drawn, 8).lit));
    same('Café', 'CAFE');
    same('ÉLAN Ñandú', 'ELAN NANDU');
    same('Straße', 'STRASSE');
    // Only what cannot be drawn so is refused, and named.
    expect(() => textBitmap('Crème €5 Æ', 8)).toThrow('The font has no “€”, “Æ”: use letters, digits and common punctuation.');
    expect(() => textBitmap('hi 🙂', 8)).toThrow(/“🙂”/);
    expect(() => textBitmap('A', 6)).toThrow(/at least 7/);
  });
  it('draws twice as large on a 14-LED strip', () => {
    const b = textBitmap('I', 14);
    expect(b.width).toBe(10);
    expect(columnBits(b).some((v) => v > 255)).toBe(true);
  });
  it('repeats side by side', () => {
    const b = textBitmap('L', 8);
    const r = repeatBitmap(b, 3);
    expect(columnBits(r)).toEqual([...columnBits(b), ...columnBits(b), ...columnBits(b)]);
  });
});

describe('imageBitmap', () => {
  const grey = (w: number, h: number, f: (x: number, y: number) => number) => {
    const rgba = new Uint8ClampedArray(w * h * 4);
    for (let y = 0; y < h; y++) for (let x = 0; x < w; x++) rgba.set([f(x, y), f(x, y), f(x, y), 255], 4 * (y * w + x));
    return rgba;
  };
  it('keeps the picture’s aspect on the machine: columns = w/h · LEDs · spacing / pitch', () => {
    const b = imageBitmap(grey(100, 50, () => 255), 100, 50, { height: 8, ledSpacing_mm: 6.4, pitch_mm: 2, halftone: 'threshold', threshold: 0.5 });
    expect(b.width).toBe(Math.round(2 * 8 * 3.2));
    expect(b.lit.every((v) => v === 1)).toBe(true);
  });
  it('thresholds a left-dark right-bright image into dark and lit halves', () => {
    const b = imageBitmap(grey(64, 8, (x) => (x < 32 ? 0 : 255)), 64, 8, { height: 8, ledSpacing_mm: 2, pitch_mm: 2, halftone: 'threshold', threshold: 0.5 });
    expect(b.width).toBe(64);
    for (let r = 0; r < 8; r++) for (let c = 0; c < 64; c++) expect(b.lit[r * 64 + c]).toBe(c < 32 ? 0 : 1);
  });
  it('dithers a flat grey to about that fraction of lit pixels (Floyd–Steinberg keeps the mean)', () => {
    fc.assert(
      fc.property(fc.double({ min: 0.05, max: 0.95, noNaN: true }), (level) => {
        const g = new Float64Array(40 * 8).fill(level);
        const out = floydSteinberg(g, 40, 8);
        const lit = out.reduce((s, v) => s + v, 0) / out.length;
        expect(Math.abs(lit - level)).toBeLessThan(0.05);
      }),
    );
  });
  it('averages by area when it shrinks', () => {
    const l = scaledLuminance(grey(4, 2, (x) => (x % 2 ? 255 : 0)), 4, 2, 2, 1);
    expect(l[0]).toBeCloseTo(0.5, 6);
  });
  it('refuses pixels that do not match the size', () => {
    expect(() => imageBitmap(new Uint8ClampedArray(10), 2, 2, { height: 8, ledSpacing_mm: 6.4, pitch_mm: 2, halftone: 'dither', threshold: 0.5 })).toThrow(/do not match/);
  });
});

describe('LED colour', () => {
  it('applies brightness then gamma per channel, and packs 0xRRGGBB exactly', () => {
    expect(ledColour([255, 128, 0], 1, 1)).toEqual([255, 128, 0]);
    expect(ledColour([255, 255, 255], 0.5, 2)).toEqual([64, 64, 64]);
    expect(packColour([255, 60, 10])).toBe(0xff3c0a);
    expect(Math.fround(packColour([255, 255, 255]))).toBe(0xffffff);
    expect(parseHexColour('#ff3c0a')).toEqual([255, 60, 10]);
    expect(parseHexColour('red')).toBeNull();
  });
});
