/**
 * The plotter tool's messages between the page and the worker. Every one carries
 * `tool: 'plotter'`; the Workbench routes commands by it. Commands are grouped by
 * their type's prefix, and plotterTool.ts routes them by it:
 *
 *   pen-*    the pen settings (axicli's pen_pos_up/down, pen_delay_up/down, speeds)
 *   draw-*   live drawing (live/liveDrawer.ts) and what the machine drew (§5)
 *   file-*   SVG and G-code import and plotting (the import module; not in this file yet)
 *
 * Points travel as flat Float64Arrays (transferred): x, y in machine mm and t, the
 * pointer event's time as epoch ms (performance.timeOrigin + event.timeStamp), so
 * the worker can place each point on the author's clock.
 */
import type { PacingStall } from '../../../core/index.ts';
import type { PenSettings } from './penSequence.ts';

export type PlotterCommand =
  | { tool: 'plotter'; type: 'pen-settings'; pen: Partial<PenSettings>; tolerance_mm?: number }
  /** A stroke starts at (x, y): the pointer went down. `id` is the page's, increasing. */
  | { tool: 'plotter'; type: 'draw-start'; id: number; x: number; y: number; t: number }
  /** More points of stroke `id`, in order: x, y, t triples. */
  | { tool: 'plotter'; type: 'draw-points'; id: number; points: Float64Array }
  /** The pointer lifted (or was cancelled): the stroke ends at its last point. */
  | { tool: 'plotter'; type: 'draw-end'; id: number }
  /** Forget the ink and strokes shown so far (the saved files start afresh). */
  | { tool: 'plotter'; type: 'draw-clear' }
  | { tool: 'plotter'; type: 'draw-save'; kind: 'drawn' | 'planned' }
  /** Dev/test hook only (docs/test-hooks.md): the simulator's truth for the e2e spec and the bench. */
  | { tool: 'plotter'; type: 'draw-truth' };

/** How far one stroke is: points received, thinned into moves, and reached by the machine. */
export interface StrokeProgress {
  id: number;
  /** Pointer points received, and the index of the last one the machine has finished drawing to (-1: none). */
  received: number;
  done: number;
  /** Whether the pointer has lifted. */
  ended: boolean;
}

export interface DrawStatus {
  strokes: StrokeProgress[];
  /** Moves waiting in the tool for room in the queue. */
  waitingMoves: number;
  /** mm of drawn path between the machine and the last point received. */
  behind_mm: number;
  /** s the machine needs for that at the draw speed. */
  behind_s: number;
  /** Whether the plotter holds the machine (strokes are being drawn). */
  active: boolean;
  /** The latest stroke id the drawer took or refused: a stroke up to it that `strokes` does not list is complete. */
  lastId: number;
}

/** Ground truth the dev/test hook returns (never built in production). */
export interface DrawTruth {
  /** Pen-down ink of the simulated pen since the last clear: x, y, t_us (author µs) triples per stroke. */
  ink: number[][];
  /**
   * Each stroke's points as the worker received them: x, y and the pointer event's
   * time, on the author's clock (µs); the author's clock when each arrived (µs);
   * and the most the machine was behind it (mm) and the most moves that waited for
   * room, as its points arrived.
   */
  strokes: Array<{ id: number; points: number[]; arrived: number[]; behindMax_mm: number; waitingMax: number }>;
  /** Author µs now, and the streamer's lead (µs). */
  now_us: number;
  lead_us: number;
  limits: { maxVelocity: number; maxAcceleration: number };
  tolerance_mm: number;
  /** Points received but not drawn (refused by the soft limits or dropped by STOP), per stroke id. */
  refusedPoints: number;
  /** Moves handed to the queue, and moves still waiting in the tool. */
  fedMoves: number;
  waitingMoves: number;
  /** The scheduler is paced (simulated machine): epoch ms ↔ author µs are exact. */
  paced: boolean;
  /** On a paced machine, the wakes of its scheduler that came late or ran long (see PacingStall). */
  stalls: readonly PacingStall[];
}

export type PlotterEvent =
  | { tool: 'plotter'; type: 'pen-settings'; pen: PenSettings; tolerance_mm: number }
  | { tool: 'plotter'; type: 'draw-status'; status: DrawStatus }
  /** The page should drop stroke `id` from its drawing (refused before anything of it was queued, or discarded). */
  | { tool: 'plotter'; type: 'stroke-refused'; id: number; reason: string }
  /** New ink since the last post: for simulated pen stroke `index`, points from `from` on (x, y pairs). */
  | { tool: 'plotter'; type: 'ink'; pieces: Array<{ index: number; from: number; xy: Float32Array }> }
  | { tool: 'plotter'; type: 'draw-cleared' }
  | { tool: 'plotter'; type: 'draw-svg'; kind: 'drawn' | 'planned'; svg: string; strokes: number }
  | { tool: 'plotter'; type: 'draw-truth'; truth: DrawTruth };
