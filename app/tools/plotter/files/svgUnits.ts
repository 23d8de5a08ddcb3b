/**
 * SVG lengths and the root viewport: how a file's user units become mm.
 *
 * CSS absolute units, with 1 px = 1/96 in (CSS Values 3): 1 in = 25.4 mm =
 * 96 px = 72 pt = 6 pc, 1 cm = 10 mm. A bare number is in user units, which are
 * px at the root when there is no viewBox.
 */

export const MM_PER_UNIT: Record<string, number> = {
  mm: 1,
  cm: 10,
  in: 25.4,
  px: 25.4 / 96,
  pt: 25.4 / 72,
  pc: 25.4 / 6,
  '': 25.4 / 96,
};

const LENGTH = /^\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*(mm|cm|in|px|pt|pc|%|em|ex)?\s*$/;

export interface Length {
  value: number;
  unit: string;
}

/** A length attribute, or null when it does not parse. */
export function parseLength(text: string): Length | null {
  const m = LENGTH.exec(text);
  if (!m) return null;
  return { value: Number(m[1]), unit: m[2] ?? '' };
}

/** A length in px (user units at 96/in); null for %, em, ex or what does not parse. */
export function lengthInPx(text: string): number | null {
  const l = parseLength(text);
  if (!l || !(l.unit in MM_PER_UNIT)) return null;
  return (l.value * MM_PER_UNIT[l.unit]) / MM_PER_UNIT.px;
}

/** A list of numbers (viewBox, points): comma- or space-separated; null if anything else is in it. */
export function parseNumberList(text: string): number[] | null {
  const values: number[] = [];
  const rest = text.replace(NUMBER, (n) => {
    values.push(Number(n));
    return ' ';
  });
  return /^[\s,]*$/.test(rest) ? values : null;
}

const NUMBER = /[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?/g;

/** The root's width or height in mm, or null when absent or relative (%). */
export function rootLengthMm(text: string | null): number | null {
  if (text === null || text.trim() === '') return null;
  const l = parseLength(text);
  if (!l || !(l.unit in MM_PER_UNIT)) return null;
  return l.value * MM_PER_UNIT[l.unit];
}

/**
 * The affine map from the root's user units to mm on the page, y down as in the
 * file (the machine's way too: x right, y down the bed, as saxi and AxiDraw lay a
 * drawing on the bed, so a drawing keeps its look and its page's top-left corner):
 * x' = a·x + c·y + e, y' = b·x + d·y + f, as svgpath's `matrix([a, b, c, d, e, f])`.
 *
 * With a viewBox (minX minY w h) and a viewport W × H mm: scale sx = W/w,
 * sy = H/h, then preserveAspectRatio ("xMidYMid meet" by default) makes them
 * equal (the smaller for meet, the larger for slice) and aligns the box in the
 * viewport. Without width/height the viewport is the viewBox in px; without a
 * viewBox, user units are px. The page's top-left corner is (0, 0).
 */
export function rootMatrix(
  width: string | null,
  height: string | null,
  viewBox: number[] | null,
  preserveAspectRatio: string | null,
): { matrix: [number, number, number, number, number, number]; width_mm: number; height_mm: number } {
  const px = MM_PER_UNIT.px;
  let W = rootLengthMm(width);
  let H = rootLengthMm(height);
  if (!viewBox) return { matrix: [px, 0, 0, px, 0, 0], width_mm: W ?? 0, height_mm: H ?? 0 };
  const [vx, vy, vw, vh] = viewBox;
  if (W === null && H === null) {
    W = vw * px;
    H = vh * px;
  } else if (W === null) W = ((H as number) * vw) / vh;
  else if (H === null) H = (W * vh) / vw;
  let sx = (W as number) / vw, sy = (H as number) / vh;
  let tx = 0, ty = 0;
  const par = (preserveAspectRatio ?? 'xMidYMid meet').trim().split(/\s+/);
  const align = par[0];
  if (align !== 'none') {
    const s = par[1] === 'slice' ? Math.max(sx, sy) : Math.min(sx, sy);
    sx = sy = s;
    const fx = align.includes('xMid') ? 0.5 : align.includes('xMax') ? 1 : 0;
    const fy = align.includes('YMid') ? 0.5 : align.includes('YMax') ? 1 : 0;
    tx = ((W as number) - vw * s) * fx;
    ty = ((H as number) - vh * s) * fy;
  }
  // mm: X = sx·(x − vx) + tx, Y = sy·(y − vy) + ty.
  return {
    matrix: [sx, 0, 0, sy, tx - sx * vx, ty - sy * vy],
    width_mm: W as number,
    height_mm: H as number,
  };
}
