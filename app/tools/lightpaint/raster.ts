/**
 * The light-painting job: one raster pass along x, its LED columns written by an
 * evaluator of the tool's planned position (the paper's Listing 5).
 *
 *   origin ─ run-up ─┬─ column 0 ─┬─ column 1 ─┬ … ┬─ column n−1 ─┬─ run-down ─ end
 *                    x0           x0 + p                          x0 + n·p
 *
 * Column c is lit over [x0 + c·p, x0 + (c+1)·p): its centre is x0 + (c + ½)·p.
 * The tool travels at y = origin y (the strip's centre); the path spans
 * [origin x, origin x + run-up + n·p + run-down], right to left when reversed
 * (the picture is the same either way: columns go by position, not by time),
 * queued in collinear pieces of at most PASS_PIECE_MM so a pause brakes mid-pass.
 *
 * Placement. The author samples the evaluator every h = evaluationPrecision
 * and holds each value until the next sample, so a value set at t is shown over
 * [t, t + h). The evaluator returns the column under the tool at the middle of
 * that interval, predicted from the state it is given:
 *
 *   x(t + h/2) ≈ x + v·h/2 + a·h²/8        (exact for the planner's constant-acceleration phases)
 *
 * so a column edge is crossed at most ±v·h/2 from where it lies (0.05 mm at
 * 200 mm/s with h = 0.5 ms), on the ramps as at cruise: columns go by where the
 * plan puts the tool, not by the time a constant speed would take. A stick that
 * times its columns instead misplaces them by up to v²/2a on a ramp.
 *
 * Light per mm: the raster move sets `neopixelColour` (the colour at cruise) and
 * `neopixelCruise` (the cruise speed); the LightPainter firmware dims the strip
 * by v / cruise from the velocity track, so every mm gets colour / cruise of
 * exposure, ramps included.
 *
 * Run-up and run-down: only what brings the tool to 20 % of cruise before the
 * first column and after the last, so the dimming never works at the 8-bit
 * floor: from rest that takes (0.2·v)² / 2a (0.4 mm at 200 mm/s and
 * 2 000 mm/s²), rounded up to 0.1 mm. The rest of each ramp lies inside the
 * picture: the evaluator places columns by position, so the pass need not
 * reach cruise before it starts writing.
 */
import type { EvaluatorState, Move, MoveEvents } from '../../../core/index.ts';
import { columnBits, type Bitmap } from './bitmap.ts';
import { packColour } from './ledColour.ts';

export const BITMAP_CHANNEL = 'neopixelBitmap';
export const COLOUR_CHANNEL = 'neopixelColour';
export const CRUISE_CHANNEL = 'neopixelCruise';

/**
 * The pass is queued in pieces no longer than PASS_PIECE_MM and no longer than
 * PASS_PIECE_S at its speed: a queued segment may run to its end once sent (the
 * streamer slices long ones only where a slice is long enough to split off, which
 * at a few mm/s it is not), so the pieces bound how far a pause or cancel runs on,
 * in time as in mm: 0.2 s at any speed (20 mm pieces at 100 mm/s; at 2 mm/s a
 * 20 mm piece ran on for 10 s after Cancel).
 */
export const PASS_PIECE_MM = 20;
export const PASS_PIECE_S = 0.2;

/** mm: the longest piece of a pass at `speed` mm/s. */
export function passPieceLength(speed: number): number {
  return Math.min(PASS_PIECE_MM, speed * PASS_PIECE_S);
}

/** ms between evaluator samples: ±0.05 mm of column edge at 200 mm/s. */
export const DEFAULT_EVALUATION_PRECISION_MS = 0.5;

export interface RasterSettings {
  /** mm/s at cruise (capped at the machine's limit along x). */
  speed: number;
  /** mm per column along the move. */
  pitch_mm: number;
  /** PWM values of a lit LED at cruise (ledColour.ts). */
  colour: readonly [number, number, number];
  /** Paint right to left. */
  reverse: boolean;
  /** ms between evaluator samples. */
  evaluationPrecision_ms: number;
  /**
   * The picture's width in mm does not depend on the pitch: an image, its aspect kept
   * (imageBitmap.ts makes w/h · LEDs · spacing / pitch columns). A finer pitch then only
   * adds columns, so a picture too wide is never offered one.
   */
  widthFixed?: boolean;
}

/** What the planner needs of the machine. */
export interface RasterMachine {
  motionAxes: readonly string[];
  eventChannels: readonly string[];
  /** mm, the work origin per motion axis. */
  origin: readonly number[];
  softMin: readonly number[];
  softMax: readonly number[];
  /** mm/s and mm/s² along +x. */
  maxSpeed: number;
  maxAccel: number;
}

/** Where the bitmap lies on the machine: what the exposure is checked against. */
export interface RasterLayout {
  /** mm, left edge of column 0. */
  x0: number;
  pitch_mm: number;
  /** Event value of each column. */
  bits: number[];
  /** mm, the tool's y while painting (the strip's centre). */
  y: number;
  /** mm, the ends of the pass along x. */
  xStart: number;
  xEnd: number;
}

export interface RasterPlan {
  moves: Move[];
  layout: RasterLayout;
  /** mm/s actually used. */
  speed: number;
  /** The requested speed, when it was above the machine's limit. */
  cappedFrom: number | null;
  runUp_mm: number;
  /** Said to the user: channels missing from the config, the speed cap. */
  notes: string[];
}

/** A job that cannot run as asked, and what would make it fit. */
export interface RasterProblem {
  error: string;
  /** mm: the pitch at which the picture fits the soft limits, if any does. */
  fitPitch_mm?: number;
}

/** mm to reach 20 % of `speed` from rest, rounded up to 0.1 mm (at least 0.1 mm). */
export function runUpLength(speed: number, accel: number): number {
  const ramp = Number.isFinite(accel) && accel > 0 ? (0.2 * speed) ** 2 / (2 * accel) : 0;
  return Math.max(0.1, Math.ceil(ramp * 10 - 1e-9) / 10);
}

/**
 * The column under x, or −1 outside the picture: columns are half-open,
 * [x0 + c·p, x0 + (c+1)·p).
 */
export function columnAt(x: number, x0: number, pitch: number, columns: number): number {
  const c = Math.floor((x - x0) / pitch);
  return c >= 0 && c < columns ? c : -1;
}

/**
 * The evaluator of Listing 5: the event value for the column the tool will be
 * over at the middle of the hold interval [t, t + h).
 */
export function bitmapEvaluator(layout: RasterLayout, axis: string, axisIndex: number, precision_ms: number): (s: EvaluatorState) => number {
  const half = precision_ms / 2000;
  return (s) => {
    const x = s.position[axis] + s.velocity[axisIndex] * half + 0.5 * s.acceleration[axisIndex] * half * half;
    const c = columnAt(x, layout.x0, layout.pitch_mm, layout.bits.length);
    return c < 0 ? 0 : layout.bits[c];
  };
}

export function planRaster(bitmap: Bitmap, s: RasterSettings, m: RasterMachine): RasterPlan | RasterProblem {
  if (!m.eventChannels.includes(BITMAP_CHANNEL)) {
    return { error: `The machine has no “${BITMAP_CHANNEL}” event channel: add it in Configure → Event channels and subscribe the LED strip's reader to it.` };
  }
  if (m.motionAxes.length === 0) return { error: 'The machine has no motion axis to paint along.' };
  if (bitmap.width === 0) return { error: 'The picture has no columns.' };
  if (!(s.pitch_mm > 0) || !Number.isFinite(s.pitch_mm)) return { error: 'The pixel pitch must be a positive number of mm.' };
  if (!(s.speed > 0) || !Number.isFinite(s.speed)) return { error: 'The speed must be a positive number of mm/s.' };
  if (!(s.evaluationPrecision_ms > 0)) return { error: 'The evaluation precision must be a positive number of ms.' };
  const notes: string[] = [];
  let speed = s.speed;
  let cappedFrom: number | null = null;
  if (speed > m.maxSpeed) {
    cappedFrom = speed;
    speed = m.maxSpeed;
    notes.push(`Speed capped at the machine's limit along x, ${m.maxSpeed} mm/s (asked ${s.speed} mm/s).`);
  }
  const axis = m.motionAxes[0];
  const n = bitmap.width;
  const runUp = runUpLength(speed, m.maxAccel);
  const width = n * s.pitch_mm;
  const total = 2 * runUp + width;
  const ox = m.origin[0];
  const room = m.softMax[0] - ox;
  if (ox < m.softMin[0] || total > room) {
    const missing = total - room;
    const fit = s.widthFixed ? null : fitPitch(n, room, speed, m.maxAccel);
    const fitPitch_mm = fit !== null && fit < s.pitch_mm ? fit : undefined;
    const shorten = s.widthFixed
      ? 'crop the image (its aspect is kept on the machine, so a finer pitch only adds columns)'
      : 'shorten the picture';
    return {
      error:
        ox < m.softMin[0]
          ? `The origin (x = ${ox} mm) is outside the soft limits [${m.softMin[0]}, ${m.softMax[0]}] mm.`
          : `The pass needs ${total.toFixed(1)} mm along ${axis} (${n} columns × ${s.pitch_mm} mm and ${runUp} mm of run-up and run-down each side), but only ${Math.max(0, room).toFixed(1)} mm lie between the origin and the soft limit at ${m.softMax[0]} mm: ${missing.toFixed(1)} mm missing. ` +
            (total <= m.softMax[0] - m.softMin[0] ? `Set the origin at ${axis} ≤ ${(m.softMax[0] - total).toFixed(1)} mm, ${shorten}` : `It is longer than the whole ${axis} range: ${shorten}`) +
            (fitPitch_mm ? `, or use a pitch of ${fitPitch_mm} mm.` : '.'),
      fitPitch_mm,
    };
  }
  for (let i = 1; i < m.motionAxes.length; i++) {
    if (m.origin[i] < m.softMin[i] || m.origin[i] > m.softMax[i]) return { error: `The origin (${m.motionAxes[i]} = ${m.origin[i]} mm) is outside the soft limits.` };
  }
  const x0 = ox + runUp;
  const layout: RasterLayout = { x0, pitch_mm: s.pitch_mm, bits: columnBits(bitmap), y: m.origin[1] ?? 0, xStart: ox, xEnd: ox + total };
  const at = (x: number) => m.motionAxes.map((_, i) => (i === 0 ? x : m.origin[i]));
  const [from, to] = s.reverse ? [layout.xEnd, layout.xStart] : [layout.xStart, layout.xEnd];

  const fixed: Array<{ name: string; value: number }> = [];
  if (m.eventChannels.includes(COLOUR_CHANNEL)) fixed.push({ name: COLOUR_CHANNEL, value: packColour(s.colour) });
  else notes.push(`No “${COLOUR_CHANNEL}” channel: the strip shows its firmware's colour.`);
  if (m.eventChannels.includes(CRUISE_CHANNEL)) fixed.push({ name: CRUISE_CHANNEL, value: speed });
  else notes.push(`No “${CRUISE_CHANNEL}” channel: the strip is not dimmed on the ramps, so the ends of the pass get more light per mm.`);
  const travelEvents: MoveEvents = { [BITMAP_CHANNEL]: 0 };
  const rasterEvents: MoveEvents = [
    { name: BITMAP_CHANNEL, evaluationPrecision: s.evaluationPrecision_ms, evaluator: bitmapEvaluator(layout, axis, 0, s.evaluationPrecision_ms) },
    ...fixed,
  ];
  // The travel to the start, strip dark, at the machine's top speed (LightBurn's
  // travel moves): at the painting speed a slow picture's travel took minutes.
  const moves: Move[] = [{ endPosition: at(from), maxVelocity: m.maxSpeed, eventChannels: travelEvents }];
  // The pass in collinear pieces (no slowing at their joints), each setting the same
  // channels: a pause or a cancel brakes within a piece or two instead of at the end.
  const pieces = Math.max(1, Math.ceil(total / passPieceLength(speed) - 1e-9));
  for (let k = 1; k <= pieces; k++) {
    const x = k === pieces ? to : from + ((to - from) * k) / pieces;
    moves.push({ endPosition: at(x), maxVelocity: speed, eventChannels: rasterEvents });
  }
  return { moves, layout, speed, cappedFrom, runUp_mm: runUp, notes };
}

/**
 * The largest pitch (rounded down to 0.01 mm) at which n columns and their
 * run-up and run-down (2r, independent of the pitch) fit in `room` mm, or null.
 */
export function fitPitch(n: number, room: number, speed: number, accel: number): number | null {
  const p = (room - 2 * runUpLength(speed, accel)) / n;
  const rounded = Math.floor(p * 100) / 100;
  return rounded > 0 ? rounded : null;
}

export function isProblem(r: RasterPlan | RasterProblem): r is RasterProblem {
  return 'error' in r;
}
