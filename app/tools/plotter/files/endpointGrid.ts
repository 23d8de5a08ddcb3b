/**
 * The free ends of a drawing's paths in a uniform grid, for "which free end is
 * nearest to this point" (linesort) and "which free end lies within the tolerance"
 * (linemerge) without scanning every path: vpype uses a spatial index for the
 * same reason.
 *
 * End ids: path i's first point is 2i, its last 2i + 1. A query looks at the
 * rings of cells around its point. The point lies inside its own cell, so every
 * cell of ring r + 1 and beyond is at least r·size away: once the nearest end
 * found is that close, no unvisited cell can hold a nearer one. Ends are removed
 * as their paths are used, so late queries do not wade through used ones. Cells
 * of about one end each (size² ≈ area / ends) keep a query near O(1) while ends
 * are dense; when k of n remain, the rings grow to about √(n/k) cells, so a whole
 * sort costs about O(n log n) cell visits.
 */
export class EndpointGrid {
  private readonly cells = new Map<number, number[]>();
  private readonly size: number;
  private minCx = Infinity;
  private minCy = Infinity;
  private maxCx = -Infinity;
  private maxCy = -Infinity;
  private count = 0;

  /** `ends`: x, y per end id. */
  constructor(private readonly ends: Float64Array) {
    const n = ends.length / 2;
    let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity;
    for (let i = 0; i < n; i++) {
      minX = Math.min(minX, ends[2 * i]);
      maxX = Math.max(maxX, ends[2 * i]);
      minY = Math.min(minY, ends[2 * i + 1]);
      maxY = Math.max(maxY, ends[2 * i + 1]);
    }
    const w = n > 0 ? maxX - minX : 0, h = n > 0 ? maxY - minY : 0;
    // About one end per cell, but at most ~2048 cells across (ends in a thin line, or nearly all in one spot).
    this.size = Math.max(Math.sqrt((Math.max(w, 1e-6) * Math.max(h, 1e-6)) / Math.max(n, 1)), Math.max(w, h) / 2048, 1e-6);
    for (let id = 0; id < n; id++) this.insert(id);
  }

  private cellOf(v: number): number {
    return Math.floor(v / this.size);
  }

  private key(cx: number, cy: number): number {
    // Exact in a double: |cx|, |cy| < 2^20 cells for any drawing on a bed.
    return (cx + 1_048_576) * 2_097_152 + (cy + 1_048_576);
  }

  private insert(id: number): void {
    const cx = this.cellOf(this.ends[2 * id]), cy = this.cellOf(this.ends[2 * id + 1]);
    this.minCx = Math.min(this.minCx, cx);
    this.maxCx = Math.max(this.maxCx, cx);
    this.minCy = Math.min(this.minCy, cy);
    this.maxCy = Math.max(this.maxCy, cy);
    const k = this.key(cx, cy);
    const list = this.cells.get(k);
    if (list) list.push(id);
    else this.cells.set(k, [id]);
    this.count++;
  }

  remove(id: number): void {
    const k = this.key(this.cellOf(this.ends[2 * id]), this.cellOf(this.ends[2 * id + 1]));
    const list = this.cells.get(k);
    const at = list ? list.indexOf(id) : -1;
    if (!list || at < 0) return;
    list[at] = list[list.length - 1];
    list.pop();
    if (list.length === 0) this.cells.delete(k);
    this.count--;
  }

  /** The free end nearest to (x, y) within `maxDistance` (inclusive), or −1. */
  nearest(x: number, y: number, maxDistance = Infinity): number {
    if (this.count === 0) return -1;
    const s = this.size;
    const cx = this.cellOf(x), cy = this.cellOf(y);
    // Only the cells over the ends' box can hold one: rings start where they meet it and stop past it.
    const i0 = this.minCx - cx, i1 = this.maxCx - cx, j0 = this.minCy - cy, j1 = this.maxCy - cy;
    const firstRing = Math.max(0, i0, -i1, j0, -j1);
    const lastRing = Math.max(-i0, i1, -j0, j1);
    let best = -1, bestD2 = maxDistance * maxDistance;
    const visit = (i: number, j: number) => {
      const list = this.cells.get(this.key(cx + i, cy + j));
      if (!list) return;
      for (const id of list) {
        const d2 = (this.ends[2 * id] - x) ** 2 + (this.ends[2 * id + 1] - y) ** 2;
        if (d2 < bestD2 || (d2 === bestD2 && (best < 0 || id < best))) {
          best = id;
          bestD2 = d2;
        }
      }
    };
    for (let r = firstRing; r <= lastRing; r++) {
      // Cells of ring r are at least (r − 1)·size away.
      if ((r - 1) * s > maxDistance) break;
      for (let i = Math.max(-r, i0); i <= Math.min(r, i1); i++) {
        if (i === -r || i === r) {
          for (let j = Math.max(-r, j0); j <= Math.min(r, j1); j++) visit(i, j);
        } else {
          if (-r >= j0) visit(i, -r);
          if (r <= j1 && r !== 0) visit(i, r);
        }
      }
      if (best >= 0 && Math.sqrt(bestD2) <= r * s) break;
    }
    return best;
  }
}
