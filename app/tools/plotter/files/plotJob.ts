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
import { lineOfSegment, type PlotPath } from './paths.ts';

/**
 * Where a move of the plot comes from: the index of its path in the paths given to
 * plotJobMoves (−1 for the pen lift before the first) and of the path's segment it
 * belongs to (the travel, pen-down and holds before a path's first segment count
 * as its segment 0, the pen lift after it as its last).
 */
export interface MoveSource {
  path: number;
  segment: number;
}

/**
 * Where a move from `source` comes from, in the user's words: the line of their file
 * (when the importer said), else its path in plotting order.
 */
export function describeSource(paths: readonly PlotPath[], source: MoveSource | undefined): string | null {
  if (!source) return null;
  if (source.path < 0) return 'the pen lift before the plot';
  const line = lineOfSegment(paths[source.path], source.segment);
  return line !== null ? `line ${line}` : `path ${source.path + 1} of ${paths.length} in plotting order`;
}

/** The job's moves; `sources`, when given, gets each move's MoveSource, index for index. */
export function plotJobMoves(paths: readonly PlotPath[], s: PenSettings, sources?: MoveSource[]): Move[] {
  const moves: Move[] = [];
  const add = (move: Move, path: number, segment: number) => {
    moves.push(move);
    sources?.push({ path, segment });
  };
  add(penUp(s), -1, 0);
  paths.forEach((p, k) => {
    const n = p.points.length / 2;
    if (n < 2) return;
    add(travelTo([p.points[0], p.points[1]], s), k, 0);
    add(penDown(s), k, 0);
    hold(p.dwells?.[0] ?? 0, (dwell) => add(dwell, k, 0));
    for (let i = 1; i < n; i++) {
      const move = drawTo([p.points[2 * i], p.points[2 * i + 1]], s);
      const own = p.speeds?.[i - 1] ?? 0;
      if (own > 0) move.maxVelocity = own;
      add(move, k, i - 1);
      hold(p.dwells?.[i] ?? 0, (dwell) => add(dwell, k, i - 1));
    }
    add(penUp(s), k, n - 2);
  });
  return moves;
}

/** A hold of `s` seconds, as dwells of at most MAX_DWELL_S each (what one segment times), each given to `add`. */
function hold(s: number, add: (dwell: Move) => void): void {
  for (let left = s; left > 0; left -= MAX_DWELL_S) add({ dwell_s: Math.min(left, MAX_DWELL_S) });
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
