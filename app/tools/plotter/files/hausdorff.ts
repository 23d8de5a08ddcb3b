/**
 * The Hausdorff distance between two sets of polylines (x, y interleaved, mm): the
 * farthest any point of one lies from the other. Points along each segment are
 * taken every `step` mm (and each vertex), and each is measured to the other
 * set's segments (not to its vertices), so the figure errs low by at most step/2.
 *
 * The segments sit in a uniform grid; a query looks at the rings of cells around
 * its point until the nearest segment found is closer than any unvisited cell.
 * For tests (import accuracy, as-drawn against the source) and benches.
 */

export class SegmentIndex {
  private readonly cells = new Map<number, number[]>();
  /** x0, y0, x1, y1 per segment. */
  private readonly segs: number[] = [];
  private readonly size: number;
  private readonly cols = 1 << 20;

  constructor(lines: readonly Float64Array[], cellSize: number) {
    this.size = cellSize;
    for (const l of lines) {
      if (l.length === 2) this.add(l[0], l[1], l[0], l[1]);
      for (let i = 2; i < l.length; i += 2) this.add(l[i - 2], l[i - 1], l[i], l[i + 1]);
    }
  }

  get empty(): boolean {
    return this.segs.length === 0;
  }

  private key(cx: number, cy: number): number {
    return (cx + this.cols / 2) * this.cols + (cy + this.cols / 2);
  }

  private add(x0: number, y0: number, x1: number, y1: number): void {
    const id = this.segs.length / 4;
    this.segs.push(x0, y0, x1, y1);
    // Every cell the segment's box touches (segments here are short against the cells).
    const s = this.size;
    for (let cx = Math.floor(Math.min(x0, x1) / s); cx <= Math.floor(Math.max(x0, x1) / s); cx++) {
      for (let cy = Math.floor(Math.min(y0, y1) / s); cy <= Math.floor(Math.max(y0, y1) / s); cy++) {
        const k = this.key(cx, cy);
        const list = this.cells.get(k);
        if (list) list.push(id);
        else this.cells.set(k, [id]);
      }
    }
  }

  /** mm from (x, y) to the nearest segment. */
  distance(x: number, y: number): number {
    const s = this.size;
    const cx = Math.floor(x / s), cy = Math.floor(y / s);
    let best = Infinity;
    for (let ring = 0; ; ring++) {
      for (let i = -ring; i <= ring; i++) {
        for (let j = -ring; j <= ring; j++) {
          if (Math.max(Math.abs(i), Math.abs(j)) !== ring) continue;
          const list = this.cells.get(this.key(cx + i, cy + j));
          if (!list) continue;
          for (const id of list) best = Math.min(best, segmentDistance(x, y, this.segs, 4 * id));
        }
      }
      // Cells beyond this ring are at least ring·s away.
      if (best <= ring * s || ring > this.cols / 4) return best;
    }
  }
}

function segmentDistance(x: number, y: number, segs: number[], o: number): number {
  const ax = segs[o], ay = segs[o + 1], dx = segs[o + 2] - ax, dy = segs[o + 3] - ay;
  const len2 = dx * dx + dy * dy;
  let t = len2 > 0 ? ((x - ax) * dx + (y - ay) * dy) / len2 : 0;
  t = Math.max(0, Math.min(1, t));
  return Math.hypot(x - (ax + t * dx), y - (ay + t * dy));
}

/** The farthest point of `from` (sampled every `step` mm) from `to`. */
export function directedHausdorff(from: readonly Float64Array[], to: readonly Float64Array[], step = 0.01): number {
  const index = new SegmentIndex(to, 1);
  if (index.empty) return from.some((l) => l.length > 0) ? Infinity : 0;
  let worst = 0;
  for (const l of from) {
    for (let i = 0; i < l.length; i += 2) {
      worst = Math.max(worst, index.distance(l[i], l[i + 1]));
      if (i + 3 >= l.length) continue;
      const dx = l[i + 2] - l[i], dy = l[i + 3] - l[i + 1];
      const n = Math.ceil(Math.hypot(dx, dy) / step);
      for (let k = 1; k < n; k++) worst = Math.max(worst, index.distance(l[i] + (dx * k) / n, l[i + 1] + (dy * k) / n));
    }
  }
  return worst;
}

export function hausdorff(a: readonly Float64Array[], b: readonly Float64Array[], step = 0.01): number {
  return Math.max(directedHausdorff(a, b, step), directedHausdorff(b, a, step));
}
