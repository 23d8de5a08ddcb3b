/**
 * The distance from a point to the nearest segment of a drawing, through a uniform
 * grid, for the Hausdorff distance (hausdorff.ts), which asks it of every sample of
 * the other drawing: a scan of every segment costs N·M for N samples and M segments
 * (4·10⁸ for a 0.02 mm check of a 4 000-segment curve), the grid about N·(a few).
 *
 * ## The grid
 * Square cells of side h over the drawing's bounding box; each segment is listed in
 * every cell its bounding box overlaps (so in every cell any of its points lies in).
 * h is the larger of the mean segment length (a segment then spans a cell or two) and
 * the side that gives 16 cells per segment (a few long segments, or a curve across a
 * wide box, do not make a huge grid of mostly empty cells).
 *
 * ## The search, and why it is exact
 * A point p falls in (or is clamped to) cell c. Visit the cells ring by ring: ring r
 * holds the cells at Chebyshev distance r from c (in cell indices). A cell of ring
 * r + 1 or more lies at least r·h from p: along the axis where its index differs by
 * r + 1, r whole cells separate it from p's cell (and if p lies outside the grid,
 * beyond its edge, further still). So once rings 0…r are done and the nearest
 * segment found is within r·h, no unvisited segment can be nearer: each segment's
 * nearest point to p lies in a cell that lists it. The answer is then the minimum
 * over a set of segments that contains the nearest one, of the same distances the
 * full scan takes (pointSegmentDistance): equal to the full scan's, bit for bit.
 */
/** A polyline: x, y pairs in mm. */
export type Polyline = ArrayLike<number>;

/** Distance from (px, py) to the segment (ax, ay)–(bx, by) (a point when a = b). */
export function pointSegmentDistance(px: number, py: number, ax: number, ay: number, bx: number, by: number): number {
  const dx = bx - ax;
  const dy = by - ay;
  const l2 = dx * dx + dy * dy;
  let t = l2 > 0 ? ((px - ax) * dx + (py - ay) * dy) / l2 : 0;
  t = t < 0 ? 0 : t > 1 ? 1 : t;
  return Math.hypot(px - (ax + t * dx), py - (ay + t * dy));
}

const CELLS_PER_SEGMENT = 16;

export class SegmentGrid {
  /** Segments as x0, y0, x1, y1 (a lone point has x1, y1 = x0, y0). */
  private readonly ends: Float64Array;
  private readonly x0: number;
  private readonly y0: number;
  private readonly cell: number;
  private readonly cols: number;
  private readonly rows: number;
  /** Cell k's segments: indices[start[k] … start[k + 1]). */
  private readonly start: Uint32Array;
  private readonly indices: Uint32Array;

  constructor(drawing: readonly Polyline[]) {
    const ends: number[] = [];
    for (const line of drawing) {
      if (line.length === 2) ends.push(line[0], line[1], line[0], line[1]);
      for (let i = 0; i + 3 < line.length; i += 2) ends.push(line[i], line[i + 1], line[i + 2], line[i + 3]);
    }
    this.ends = Float64Array.from(ends);
    const n = this.ends.length / 4;
    let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity, length = 0;
    for (let s = 0; s < n; s++) {
      const [ax, ay, bx, by] = this.segment(s);
      minX = Math.min(minX, ax, bx);
      maxX = Math.max(maxX, ax, bx);
      minY = Math.min(minY, ay, by);
      maxY = Math.max(maxY, ay, by);
      length += Math.hypot(bx - ax, by - ay);
    }
    const w = n > 0 ? maxX - minX : 0;
    const h = n > 0 ? maxY - minY : 0;
    // See "The grid": the mean segment length, or 16 cells per segment; never 0.
    this.cell = Math.max(n > 0 ? length / n : 0, Math.sqrt((w * h) / Math.max(1, CELLS_PER_SEGMENT * n)), (w + h) / 4096, 1e-9);
    this.x0 = n > 0 ? minX : 0;
    this.y0 = n > 0 ? minY : 0;
    this.cols = Math.floor(w / this.cell) + 1;
    this.rows = Math.floor(h / this.cell) + 1;
    // Two passes (count, then fill) into one flat index array.
    const count = new Uint32Array(this.cols * this.rows + 1);
    this.forEachCellOf(n, (k) => count[k + 1]++);
    for (let k = 1; k < count.length; k++) count[k] += count[k - 1];
    this.start = count.slice();
    this.indices = new Uint32Array(count[count.length - 1]);
    const fill = count.slice(0, -1);
    this.forEachCellOf(n, (k, s) => (this.indices[fill[k]++] = s));
  }

  /** Distance from (px, py) to the nearest segment or lone point; Infinity for an empty drawing. */
  distance(px: number, py: number): number {
    if (this.ends.length === 0) return Infinity;
    const cx = this.clamp(Math.floor((px - this.x0) / this.cell), this.cols);
    const cy = this.clamp(Math.floor((py - this.y0) / this.cell), this.rows);
    const rings = Math.max(cx, this.cols - 1 - cx, cy, this.rows - 1 - cy);
    let best = Infinity;
    for (let r = 0; r <= rings; r++) {
      for (let y = cy - r; y <= cy + r; y++) {
        if (y < 0 || y >= this.rows) continue;
        // The ring's top and bottom rows whole; the rows between, only their two ends.
        const stepX = y === cy - r || y === cy + r ? 1 : 2 * r;
        for (let x = cx - r; x <= cx + r; x += Math.max(1, stepX)) {
          if (x < 0 || x >= this.cols) continue;
          const k = y * this.cols + x;
          for (let j = this.start[k]; j < this.start[k + 1]; j++) {
            const s = this.indices[j] * 4;
            const e = this.ends;
            const d = pointSegmentDistance(px, py, e[s], e[s + 1], e[s + 2], e[s + 3]);
            if (d < best) best = d;
          }
        }
      }
      // (1 − 10⁻⁹: a point on a cell's edge may round into its neighbour.)
      if (best <= r * this.cell * (1 - 1e-9)) break;
    }
    return best;
  }

  private segment(s: number): [number, number, number, number] {
    const e = this.ends;
    return [e[4 * s], e[4 * s + 1], e[4 * s + 2], e[4 * s + 3]];
  }

  private clamp(i: number, size: number): number {
    return i < 0 ? 0 : i >= size ? size - 1 : i;
  }

  /** Calls visit(cell, segment) for every cell each segment's bounding box overlaps. */
  private forEachCellOf(n: number, visit: (cell: number, segment: number) => void): void {
    for (let s = 0; s < n; s++) {
      const [ax, ay, bx, by] = this.segment(s);
      const xFrom = this.clamp(Math.floor((Math.min(ax, bx) - this.x0) / this.cell), this.cols);
      const xTo = this.clamp(Math.floor((Math.max(ax, bx) - this.x0) / this.cell), this.cols);
      const yFrom = this.clamp(Math.floor((Math.min(ay, by) - this.y0) / this.cell), this.rows);
      const yTo = this.clamp(Math.floor((Math.max(ay, by) - this.y0) / this.cell), this.rows);
      for (let y = yFrom; y <= yTo; y++) for (let x = xFrom; x <= xTo; x++) visit(y * this.cols + x, s);
    }
  }
}
