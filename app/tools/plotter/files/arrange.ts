/**
 * Placing a drawing on the bed: rotate, scale (or fit), place; all in mm.
 *
 * The drawing is rotated by quarter turns (clockwise as seen on the bed, whose y
 * runs down the page) about its bounding box's centre,
 * then scaled about it, then placed:
 * - `center`: its box's centre goes to the centre of the area (the soft limits);
 * - `file`: it keeps the file's own coordinates, offset by the work origin (a
 *   G-code file's X0 Y0 is the origin; an SVG page's top-left corner is).
 * `fit` picks the largest scale at which the rotated drawing fits inside the area
 * less the margin on every side, and centres it.
 *
 * A drawing that does not fit is never clipped: the result says so (`fits`), the
 * panel offers Fit, and the plot is refused until it fits.
 */
import { boundsOf, type Bounds, type PlotPath } from './paths.ts';

export interface Arrangement {
  /** Quarter turns, clockwise as seen on the bed (x right, y down): 0, 90, 180 or 270 degrees. */
  rotate_deg: 0 | 90 | 180 | 270;
  /** Scale to fit the area less the margin (ignores `scale` and `place`). */
  fit: boolean;
  /** Used when not fitting: 1 is the file's true size. */
  scale: number;
  place: 'center' | 'file';
  /** mm kept free on every side when fitting. */
  margin_mm: number;
}

export const DEFAULT_ARRANGEMENT: Arrangement = { rotate_deg: 0, fit: false, scale: 1, place: 'center', margin_mm: 5 };

/** The area the drawing goes in: the machine's soft limits in x and y, mm. */
export interface Area {
  minX: number;
  minY: number;
  maxX: number;
  maxY: number;
}

/** x' = a·x + c·y + e, y' = b·x + d·y + f. */
export type Affine = [number, number, number, number, number, number];

export interface Placed {
  paths: PlotPath[];
  matrix: Affine;
  /** The scale used (the fit's when fitting). */
  scale: number;
  bounds: Bounds;
  /** Whether the placed drawing lies inside the area (null when there is no area). */
  fits: boolean | null;
  /** The scale that would fit it (null without an area). */
  fitScale: number | null;
}

export function applyAffine(m: Affine, x: number, y: number): [number, number] {
  return [m[0] * x + m[2] * y + m[4], m[1] * x + m[3] * y + m[5]];
}

export function transformPaths(paths: readonly PlotPath[], m: Affine): PlotPath[] {
  return paths.map((p) => {
    const points = new Float64Array(p.points.length);
    for (let i = 0; i < points.length; i += 2) {
      points[i] = m[0] * p.points[i] + m[2] * p.points[i + 1] + m[4];
      points[i + 1] = m[1] * p.points[i] + m[3] * p.points[i + 1] + m[5];
    }
    return { points, speeds: p.speeds, dwells: p.dwells, lines: p.lines };
  });
}

/** A point strictly inside the area by more than this is inside (rounding of the placement). */
const INSIDE_EPS = 1e-9;

export function arrange(paths: readonly PlotPath[], a: Arrangement, area: Area | null, origin: readonly [number, number]): Placed {
  const b = boundsOf(paths);
  if (!b) throw new Error('arrange: a drawing with no points');
  const cx = (b.minX + b.maxX) / 2, cy = (b.minY + b.maxY) / 2;
  const turns = ((a.rotate_deg / 90) % 4 + 4) % 4;
  const cos = [1, 0, -1, 0][turns], sin = [0, 1, 0, -1][turns];
  const quarter = turns % 2 === 1;
  const w = quarter ? b.maxY - b.minY : b.maxX - b.minX;
  const h = quarter ? b.maxX - b.minX : b.maxY - b.minY;
  let fitScale: number | null = null;
  if (area) {
    const aw = area.maxX - area.minX - 2 * a.margin_mm, ah = area.maxY - area.minY - 2 * a.margin_mm;
    const sx = w > 0 ? aw / w : Infinity, sy = h > 0 ? ah / h : Infinity;
    const s = Math.min(sx, sy);
    fitScale = Number.isFinite(s) && s > 0 ? s : null;
  }
  const scale = a.fit && fitScale !== null ? fitScale : a.scale;
  // Where the box's centre goes.
  let tx: number, ty: number;
  if ((a.fit || a.place === 'center') && area) {
    tx = (area.minX + area.maxX) / 2;
    ty = (area.minY + area.maxY) / 2;
  } else {
    // `file`: rotation and scale about the box's centre, which stays where the file puts it.
    tx = origin[0] + cx;
    ty = origin[1] + cy;
  }
  // p' = t + s·R·(p − c)
  const m: Affine = [scale * cos, scale * sin, -scale * sin, scale * cos, 0, 0];
  m[4] = tx - (m[0] * cx + m[2] * cy);
  m[5] = ty - (m[1] * cx + m[3] * cy);
  const placed = transformPaths(paths, m);
  const pb = boundsOf(placed) as Bounds;
  const fits = area
    ? pb.minX >= area.minX - INSIDE_EPS && pb.maxX <= area.maxX + INSIDE_EPS && pb.minY >= area.minY - INSIDE_EPS && pb.maxY <= area.maxY + INSIDE_EPS
    : null;
  return { paths: placed, matrix: m, scale, bounds: pb, fits, fitScale };
}
