/**
 * A live stroke against the soft limits (a box in machine mm), point by point:
 * the parts inside are drawn, the parts outside are refused. Where the stroke
 * leaves the box, the piece ends exactly on the boundary (pen up); where it comes
 * back, a new piece starts on the boundary (travel there, pen down).
 *
 * Each step clips the segment p→q with Liang–Barsky: writing the segment as
 * p + t·(q − p), t ∈ [0, 1], each of the four box sides bounds t from one side,
 *   min_i ≤ p_i + t·d_i ≤ max_i   (d = q − p)
 * so for d_i > 0: t ≥ (min_i − p_i)/d_i and t ≤ (max_i − p_i)/d_i, the other way
 * round for d_i < 0, and for d_i = 0 the segment is wholly in or out on that
 * axis. The segment's part inside is [t0, t1] = [max of the lower bounds, min of
 * the upper ones], empty when t0 > t1.
 */
import type { Point } from './thinning.ts';

export type ClipStep =
  | { type: 'start'; p: Point } // a piece starts here (travel, pen down)
  | { type: 'to'; p: Point } //    draw to here
  | { type: 'end' }; //            the piece ends at the last point (pen up)

/** The part of segment a→b inside the box as [t0, t1] ⊆ [0, 1], or null if none. */
export function clipSegment(a: Point, b: Point, min: readonly number[], max: readonly number[]): [number, number] | null {
  let t0 = 0;
  let t1 = 1;
  for (let i = 0; i < 2; i++) {
    const d = b[i] - a[i];
    if (d === 0) {
      if (a[i] < min[i] || a[i] > max[i]) return null;
      continue;
    }
    let lo = (min[i] - a[i]) / d;
    let hi = (max[i] - a[i]) / d;
    if (d < 0) [lo, hi] = [hi, lo];
    if (lo > t0) t0 = lo;
    if (hi < t1) t1 = hi;
    if (t0 > t1) return null;
  }
  return [t0, t1];
}

function inside(p: Point, min: readonly number[], max: readonly number[]): boolean {
  return p[0] >= min[0] && p[0] <= max[0] && p[1] >= min[1] && p[1] <= max[1];
}

function clamp(v: number, lo: number, hi: number): number {
  return v < lo ? lo : v > hi ? hi : v;
}

export class StrokeClipper {
  private last: Point | null = null;
  /** Whether a piece is open (the pen is down at `last`). */
  private open = false;
  /** mm of the stroke refused so far. */
  refused_mm = 0;
  /** The first point that was refused, if any. */
  firstRefused: Point | null = null;

  constructor(
    readonly min: readonly number[],
    readonly max: readonly number[],
  ) {}

  /** The point at t along a→b, clamped into the box: a boundary point computed in floating point may land a hair outside. */
  private at(a: Point, b: Point, t: number): Point {
    if (t === 0) return a;
    if (t === 1) return b;
    return [clamp(a[0] + (b[0] - a[0]) * t, this.min[0], this.max[0]), clamp(a[1] + (b[1] - a[1]) * t, this.min[1], this.max[1])];
  }

  /** The next point of the stroke; returns what to do. */
  push(q: Point): ClipStep[] {
    const p = this.last;
    this.last = q;
    if (p === null) {
      if (inside(q, this.min, this.max)) {
        this.open = true;
        return [{ type: 'start', p: q }];
      }
      this.firstRefused ??= q;
      return [];
    }
    const length = Math.hypot(q[0] - p[0], q[1] - p[1]);
    const span = clipSegment(p, q, this.min, this.max);
    if (span === null) {
      this.refused_mm += length;
      this.firstRefused ??= q;
      return [];
    }
    const [t0, t1] = span;
    this.refused_mm += length * (t0 + (1 - t1));
    const steps: ClipStep[] = [];
    if (!this.open) {
      // Only grazing the box (a corner, or a point on its edge on the way out): nothing to draw.
      if (t1 === t0 && t1 < 1) return steps;
      steps.push({ type: 'start', p: this.at(p, q, t0) });
      this.open = true;
    }
    if (t1 > t0) steps.push({ type: 'to', p: this.at(p, q, t1) });
    if (t1 < 1) {
      this.firstRefused ??= q;
      steps.push({ type: 'end' });
      this.open = false;
    }
    return steps;
  }

  /** The stroke ended: closes an open piece. */
  finish(): ClipStep[] {
    if (!this.open) return [];
    this.open = false;
    return [{ type: 'end' }];
  }
}
