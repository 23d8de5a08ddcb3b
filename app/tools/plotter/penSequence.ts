/**
 * The pen as moves: what every plotter job and every live stroke is made of.
 *
 *   travel (pen up, at the travel speed) to the stroke's first point
 *   pen down: a dwell that sets the pen channel to `down` at its start and holds
 *             the machine at rest for `delayDown_s`, so the servo lands before
 *             the stroke starts
 *   the stroke's points, at the drawing speed
 *   pen up: a dwell that sets the channel to `up` and holds for `delayUp_s`, so
 *           the pen has left the paper before the carriage travels
 *
 * The settings follow axicli's (pen_pos_up/down, pen_delay_up/down); positions
 * are machine mm, named by axis so that other motion axes (a z, say) stay put.
 */
import type { DwellMove, LinearMove, Move } from '../../../core/index.ts';

export interface PenSettings {
  /** The event channel that drives the pen (`pen` on the Blot preset). */
  channel: string;
  /** Channel values for the pen up and down. */
  up: number;
  down: number;
  /** s the machine waits after each command, for the servo to swing. */
  delayUp_s: number;
  delayDown_s: number;
  /** mm/s with the pen down, and travelling with it up. */
  drawSpeed: number;
  travelSpeed: number;
  /** The two motion axes the drawing lies in. */
  axes: readonly [string, string];
}

/** A stroke: its points in machine mm, in drawing order, [x, y] each. */
export type Stroke = readonly (readonly [number, number])[];

export function penDown(s: PenSettings): DwellMove {
  return { dwell_s: s.delayDown_s, eventChannels: { [s.channel]: s.down } };
}

export function penUp(s: PenSettings): DwellMove {
  return { dwell_s: s.delayUp_s, eventChannels: { [s.channel]: s.up } };
}

export function travelTo(p: readonly [number, number], s: PenSettings): LinearMove {
  return { endPosition: { [s.axes[0]]: p[0], [s.axes[1]]: p[1] }, maxVelocity: s.travelSpeed };
}

export function drawTo(p: readonly [number, number], s: PenSettings): LinearMove {
  return { endPosition: { [s.axes[0]]: p[0], [s.axes[1]]: p[1] }, maxVelocity: s.drawSpeed };
}

/** One whole stroke, pen up at both ends: travel, pen down, the points, pen up. */
export function strokeMoves(stroke: Stroke, s: PenSettings): Move[] {
  if (stroke.length === 0) return [];
  const moves: Move[] = [travelTo(stroke[0], s), penDown(s)];
  for (let i = 1; i < stroke.length; i++) moves.push(drawTo(stroke[i], s));
  moves.push(penUp(s));
  return moves;
}

/**
 * A whole drawing. It starts with the pen lifted, whatever state it was left in,
 * and ends with it lifted.
 */
export function plotMoves(strokes: readonly Stroke[], s: PenSettings): Move[] {
  const moves: Move[] = [penUp(s)];
  for (const stroke of strokes) moves.push(...strokeMoves(stroke, s));
  return moves;
}
