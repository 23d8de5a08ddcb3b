/**
 * Thinning a live stroke by distance, point by point as the pointer moves: a
 * point is kept only if it lies at least `tolerance_mm` from the last kept one.
 * A pen tablet reports ~200 points a second and a mouse ~125, most of them a
 * fraction of a millimetre apart; every kept point becomes a segment in the
 * machine's queue, so the tolerance bounds the segment count by the stroke's
 * length (≤ length / tolerance + 1) while the kept polyline stays within the
 * tolerance of every dropped point (each dropped point lies inside the circle of
 * radius tolerance around the point kept before it).
 *
 * The last point of a stroke is always kept (`finish`), so the stroke ends where
 * the pointer lifted.
 */
export type Point = readonly [number, number];

export class DistanceThinner {
  private last: Point | null = null;
  /** The last point offered but not kept. */
  private skipped: Point | null = null;

  constructor(readonly tolerance_mm: number) {
    if (!(tolerance_mm >= 0) || !Number.isFinite(tolerance_mm)) throw new RangeError(`the thinning tolerance must be a finite distance ≥ 0 mm, got ${tolerance_mm}`);
  }

  /** Whether `p` is kept. The first point always is. */
  push(p: Point): boolean {
    if (this.last === null || Math.hypot(p[0] - this.last[0], p[1] - this.last[1]) >= this.tolerance_mm) {
      this.last = p;
      this.skipped = null;
      return true;
    }
    this.skipped = p;
    return false;
  }

  /** The stroke's last point if it was not kept (the pointer lifted there), else null. */
  finish(): Point | null {
    const p = this.skipped;
    this.skipped = null;
    if (p === null || this.last === null || (p[0] === this.last[0] && p[1] === this.last[1])) return null;
    this.last = p;
    return p;
  }
}
