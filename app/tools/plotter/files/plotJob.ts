/**
 * The placed drawing as the machine's moves, and the exact plot time.
 *
 * The moves are penSequence.ts's (pen up first; per path: travel, pen down, the
 * points, pen up), with two additions a file can ask for: a segment's own speed
 * (a G-code F) and a hold at a point (a G-code G4 inside a stroke).
 *
 * The plot time is not estimated from lengths and speeds: it is planPath's
 * duration for the very moves the job will queue, from the position the job
 * starts at, with the dwells, the machine's limits and the link's floor on
 * segment durations (maxl.feedLimit) that the queue applies on a slow link.
 */
import { isDwell, MAX_DWELL_S, planPath, type LimitsConfig, type Move, type PathMove } from '../../../../core/index.ts';
import { drawTo, penDown, penUp, travelTo, type PenSettings } from '../penSequence.ts';
import type { PlotPath } from './paths.ts';

export function plotJobMoves(paths: readonly PlotPath[], s: PenSettings): Move[] {
  const moves: Move[] = [penUp(s)];
  for (const p of paths) {
    const n = p.points.length / 2;
    if (n < 2) continue;
    moves.push(travelTo([p.points[0], p.points[1]], s), penDown(s));
    hold(moves, p.dwells?.[0] ?? 0);
    for (let i = 1; i < n; i++) {
      const move = drawTo([p.points[2 * i], p.points[2 * i + 1]], s);
      const own = p.speeds?.[i - 1] ?? 0;
      if (own > 0) move.maxVelocity = own;
      moves.push(move);
      hold(moves, p.dwells?.[i] ?? 0);
    }
    moves.push(penUp(s));
  }
  return moves;
}

/** A hold of `s` seconds, as dwells of at most MAX_DWELL_S each (what one segment times). */
function hold(moves: Move[], s: number): void {
  for (let left = s; left > 0; left -= MAX_DWELL_S) moves.push({ dwell_s: Math.min(left, MAX_DWELL_S) });
}

/**
 * The moves as planPath takes them: positions made whole from `start` (a move
 * names only the axes it changes), dwells as they are.
 */
export function pathMoves(moves: readonly Move[], axes: readonly string[], start: readonly number[]): PathMove[] {
  const out: PathMove[] = [];
  let at = [...start];
  for (const m of moves) {
    if (isDwell(m)) {
      out.push({ dwell_s: m.dwell_s });
      continue;
    }
    const end = m.endPosition;
    at = [...at];
    if (Array.isArray(end)) at = [...end];
    else {
      for (const [axis, v] of Object.entries(end)) {
        const i = axes.indexOf(axis);
        if (i < 0) throw new Error(`"${axis}" is not a motion axis (${axes.join(', ')})`);
        at[i] = v;
      }
    }
    out.push(m.maxVelocity === undefined ? { end: at } : { end: at, maxVelocity: m.maxVelocity });
  }
  return out;
}

/** s: the planner's own duration of the job, from `start`, with the link's floor `minSegment_us`. */
export function plotTime(moves: readonly Move[], axes: readonly string[], start: readonly number[], limits: LimitsConfig, minSegment_us: number): number {
  return planPath([...start], pathMoves(moves, axes, start), limits, { minSegment_us }).duration;
}
