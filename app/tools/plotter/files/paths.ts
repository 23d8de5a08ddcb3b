/**
 * What an imported file becomes: pen-down polylines in mm, and what the user must
 * hear about it. Both importers (SVG, G-code) produce this; ordering, merging,
 * arranging on the bed and the plot job work on it.
 */

/** One pen-down polyline. */
export interface PlotPath {
  /** x, y interleaved, mm; at least 2 points. */
  points: Float64Array;
  /**
   * mm/s for each segment (points/2 − 1 of them), segment i ending at point i + 1;
   * 0 for "the pen-down speed setting". Null when every segment uses the setting.
   */
  speeds: Float64Array | null;
  /** s to hold at each point once reached, pen down (a G4 inside a stroke); null when none. */
  dwells: Float64Array | null;
  /**
   * The file's 1-based line each segment comes from (as `speeds`: segment i ends at
   * point i + 1), 0 where unknown; absent or null when the importer does not say.
   * For telling the user which line of their file a refused move comes from.
   */
  lines?: Int32Array | null;
}

/** The file's line that segment i of `p` comes from (clamped to its segments), or null when unknown. */
export function lineOfSegment(p: PlotPath, i: number): number | null {
  const lines = p.lines;
  if (!lines || lines.length === 0) return null;
  const line = lines[Math.max(0, Math.min(lines.length - 1, i))];
  return line > 0 ? line : null;
}

/** Something the user must know about the file: where (a line, an element) and what. */
export interface FileWarning {
  /** 1-based line in the file, when known. */
  line?: number;
  message: string;
}

/**
 * An imported file. Drawing coordinates are mm, x right and y down the bed (the
 * machine's coordinates, as saxi and AxiDraw lay a drawing on the bed): an SVG
 * keeps its page's axes, a G-code file its own X and Y.
 */
export interface Drawing {
  name: string;
  kind: 'svg' | 'gcode';
  paths: PlotPath[];
  warnings: FileWarning[];
}

/** A bad file: the whole import is refused, with where and what. */
export class FileImportError extends Error {
  constructor(
    message: string,
    readonly line?: number,
  ) {
    super(line !== undefined ? `line ${line}: ${message}` : message);
    this.name = 'FileImportError';
  }
}

export function pointCount(p: PlotPath): number {
  return p.points.length / 2;
}

export function pathFromPoints(xy: readonly number[] | Float64Array): PlotPath {
  return { points: Float64Array.from(xy), speeds: null, dwells: null };
}

/** The same path drawn from its other end. */
export function reversed(p: PlotPath): PlotPath {
  const n = pointCount(p);
  const points = new Float64Array(p.points.length);
  for (let i = 0; i < n; i++) {
    points[2 * i] = p.points[2 * (n - 1 - i)];
    points[2 * i + 1] = p.points[2 * (n - 1 - i) + 1];
  }
  // Segment i (points i → i+1) becomes segment n − 2 − i.
  const speeds = p.speeds ? p.speeds.slice().reverse() : null;
  const dwells = p.dwells ? p.dwells.slice().reverse() : null;
  const lines = p.lines ? p.lines.slice().reverse() : null;
  return { points, speeds, dwells, lines };
}

/** mm of pen-down drawing. */
export function pathLength(p: PlotPath): number {
  let total = 0;
  for (let i = 2; i < p.points.length; i += 2) total += Math.hypot(p.points[i] - p.points[i - 2], p.points[i + 1] - p.points[i - 1]);
  return total;
}

/** mm of pen-up travel from `start` through the paths in order (no return at the end). */
export function travelLength(paths: readonly PlotPath[], start: readonly [number, number]): number {
  let total = 0;
  let x = start[0], y = start[1];
  for (const p of paths) {
    total += Math.hypot(p.points[0] - x, p.points[1] - y);
    x = p.points[p.points.length - 2];
    y = p.points[p.points.length - 1];
  }
  return total;
}

export interface Bounds {
  minX: number;
  minY: number;
  maxX: number;
  maxY: number;
}

export function boundsOf(paths: readonly PlotPath[]): Bounds | null {
  let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity;
  for (const p of paths) {
    for (let i = 0; i < p.points.length; i += 2) {
      const x = p.points[i], y = p.points[i + 1];
      if (x < minX) minX = x;
      if (x > maxX) maxX = x;
      if (y < minY) minY = y;
      if (y > maxY) maxY = y;
    }
  }
  return minX <= maxX ? { minX, minY, maxX, maxY } : null;
}
