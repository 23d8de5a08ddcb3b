/**
 * Follows a carriage along a polyline: how far along the path it is (arc length,
 * mm), how far off it, and whether it ever went back or jumped ahead. A job that
 * loses nothing and runs nothing twice moves monotonically along its path, on it,
 * to its end.
 *
 * The projection is tracked: each sample is projected onto the polyline pieces
 * next to the previous one's; among the nearest (within NEAR_MM) it takes the least
 * arc length not behind the previous one, else the one closest to it. So a path
 * that doubles back over itself (a 1-D job) is still followed piece by piece.
 */
/**
 * Pieces this much (mm) farther than the nearest still count as near: a carriage a
 * little off its path (a restarted board resumes from an estimate, off by ~0.1 mm)
 * still follows it piece by piece where the path doubles back over itself.
 */
const NEAR_MM = 0.2;

export class PathTracker {
  private readonly cumulative: number[] = [0];
  private piece = 0;
  /** Arc length of the last sample (mm). */
  s = 0;
  /** Largest step back along the path between two samples (mm). */
  worstBack = 0;
  /** Largest distance from the path over all samples (mm). */
  worstOff = 0;
  /** Largest distance ahead along the path between two samples (mm). */
  worstAhead = 0;

  constructor(readonly points: readonly (readonly number[])[]) {
    for (let k = 1; k < points.length; k++) this.cumulative.push(this.cumulative[k - 1] + Math.hypot(...points[k].map((v, i) => v - points[k - 1][i])));
  }

  get length(): number {
    return this.cumulative[this.cumulative.length - 1];
  }

  /** Projects one sample; returns its distance from the path (mm, to the nearest piece looked at). */
  add(p: readonly number[]): number {
    let best: { d: number; s: number; piece: number } | null = null;
    const candidates: Array<{ d: number; s: number; piece: number }> = [];
    for (let k = Math.max(0, this.piece - 1); k <= Math.min(this.points.length - 2, this.piece + 2); k++) {
      const a = this.points[k];
      const b = this.points[k + 1];
      const ab = a.map((v, i) => b[i] - v);
      const len2 = ab.reduce((sum, v) => sum + v * v, 0);
      const t = len2 === 0 ? 0 : Math.max(0, Math.min(1, ab.reduce((sum, v, i) => sum + v * (p[i] - a[i]), 0) / len2));
      const d = Math.hypot(...a.map((v, i) => v + t * ab[i] - p[i]));
      const c = { d, s: this.cumulative[k] + t * Math.sqrt(len2), piece: k };
      candidates.push(c);
      if (!best || d < best.d) best = c;
    }
    const near = candidates.filter((c) => c.d <= (best as { d: number }).d + NEAR_MM);
    // Forward first: the nearest arc length not behind the last (by more than 1 µm); else the nearest.
    const ahead = near.filter((c) => c.s >= this.s - 1e-3);
    const chosen = ahead.length > 0 ? ahead.reduce((x, y) => (y.s < x.s ? y : x)) : near.reduce((x, y) => (Math.abs(y.s - this.s) < Math.abs(x.s - this.s) ? y : x));
    this.worstBack = Math.max(this.worstBack, this.s - chosen.s);
    this.worstAhead = Math.max(this.worstAhead, chosen.s - this.s);
    // Off the path: the distance to the nearest piece, whichever the arc length was taken from.
    const off = (best as { d: number }).d;
    this.worstOff = Math.max(this.worstOff, off);
    this.s = chosen.s;
    this.piece = chosen.piece;
    return off;
  }
}
