/**
 * Pen strokes as an SVG file in millimetres: what "Save as drawn" and "Save as
 * planned" write. The viewBox is in mm and width/height carry the "mm" unit, so
 * one user unit is one millimetre in any SVG program (Inkscape, a browser, saxi).
 * Each stroke is one <polyline>, in drawing order. SVG coordinates are machine
 * coordinates (x right, y down the page, as AxiDraw and saxi map a drawing onto
 * the bed, and as the bed view shows it): a file saved here and imported again
 * lands where it was drawn.
 */

/** One stroke: x, y pairs in machine mm. */
export type FlatStroke = ArrayLike<number>;

export interface SvgOptions {
  /** The page, machine mm: [xmin, ymin, xmax, ymax] (the soft limits, say). */
  page: readonly [number, number, number, number];
  /** Goes into <title> and a comment. */
  title: string;
  /** Stroke width, mm (the pen's). Default 0.4. */
  penWidth_mm?: number;
  /** Decimal places of the coordinates. Default 3 (1 µm). */
  digits?: number;
}

function escapeXml(s: string): string {
  return s.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;').replace(/"/g, '&quot;');
}

/** Formats a number with at most `digits` decimals and no trailing zeros. */
function num(v: number, digits: number): string {
  const s = v.toFixed(digits);
  return s.includes('.') ? s.replace(/0+$/, '').replace(/\.$/, '') : s;
}

export function strokesToSvg(strokes: readonly FlatStroke[], o: SvgOptions): string {
  const [x0, y0, x1, y1] = o.page;
  if (!(x1 > x0 && y1 > y0)) throw new RangeError(`the page must have a positive size, got [${o.page.join(', ')}] mm`);
  const digits = o.digits ?? 3;
  const w = num(x1 - x0, digits);
  const h = num(y1 - y0, digits);
  const lines = [
    '<?xml version="1.0" encoding="UTF-8"?>',
    `<svg xmlns="http://www.w3.org/2000/svg" width="${w}mm" height="${h}mm" viewBox="${num(x0, digits)} ${num(y0, digits)} ${w} ${h}">`,
    `  <title>${escapeXml(o.title)}</title>`,
    `  <g fill="none" stroke="black" stroke-width="${num(o.penWidth_mm ?? 0.4, digits)}" stroke-linecap="round" stroke-linejoin="round">`,
  ];
  for (const s of strokes) {
    if (s.length < 2) continue;
    const pts: string[] = [];
    for (let i = 0; i + 1 < s.length; i += 2) pts.push(`${num(s[i], digits)},${num(s[i + 1], digits)}`);
    // A single point (a dot) still shows: a polyline needs two.
    if (pts.length === 1) pts.push(pts[0]);
    lines.push(`    <polyline points="${pts.join(' ')}"/>`);
  }
  lines.push('  </g>', '</svg>', '');
  return lines.join('\n');
}

/**
 * Reads back what strokesToSvg wrote: each polyline's points in machine mm. For
 * tests and for comparing a drawn and a planned file (not a general SVG reader).
 */
export function svgStrokes(svg: string): number[][] {
  const out: number[][] = [];
  for (const m of svg.matchAll(/<polyline points="([^"]*)"/g)) {
    const xy: number[] = [];
    for (const pair of m[1].trim().split(/\s+/)) {
      const [x, y] = pair.split(',').map(Number);
      xy.push(x, y);
    }
    out.push(xy);
  }
  return out;
}
