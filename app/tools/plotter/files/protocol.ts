/**
 * The plotter's file commands and events (SVG and G-code import, arrange, plot),
 * between the page's ImportPanel and the worker's fileJobs.ts. Every one carries
 * `tool: 'plotter'` and a `file-*` type.
 */
import type { Arrangement } from './arrange.ts';
import type { GcodePenMode } from './gcodeImport.ts';
import type { FileWarning } from './paths.ts';
import type { PreviewLayer } from './previewLayer.ts';

export type FileKind = 'svg' | 'gcode';

/** How a file is read; changing any of these reads the file again. */
export interface ImportSettings {
  /** mm: the greatest distance between a curve and its chords. */
  chordTolerance_mm: number;
  /** G-code: how the pen is driven. */
  gcodePen: GcodePenMode;
  /** mm: G-code in Z mode, the pen is down while Z is below this. */
  zThreshold_mm: number;
}

/** How the drawing is plotted; changing these re-plans the preview. */
export interface PlotSettings {
  arrangement: Arrangement;
  /** Join paths whose ends touch (linemerge). */
  merge: boolean;
  mergeTolerance_mm: number;
  /** Reorder paths to cut pen-up travel (linesort). */
  sort: boolean;
  /** mm/s with the pen down (G-code F overrides it per move) and travelling. */
  drawSpeed: number;
  travelSpeed: number;
  /** s the machine waits for the pen to land, and to lift. */
  penDelayDown_s: number;
  penDelayUp_s: number;
}

export type FileCommand =
  | { tool: 'plotter'; type: 'file-load'; name: string; text: string; import: ImportSettings; plot: PlotSettings }
  | { tool: 'plotter'; type: 'file-settings'; import: ImportSettings; plot: PlotSettings }
  | { tool: 'plotter'; type: 'file-plot' }
  | { tool: 'plotter'; type: 'file-clear' };

export interface FileSummary {
  name: string;
  kind: FileKind;
  paths: number;
  points: number;
  /** mm, the drawing's size as imported (before scaling). */
  width_mm: number;
  height_mm: number;
}

export interface PreviewStats {
  /** The scale in use, and the one that would fit the area less the margin. */
  scale: number;
  fitScale: number | null;
  /** mm, the placed drawing's size. */
  width_mm: number;
  height_mm: number;
  /** Whether it lies inside the soft limits (null: the machine has none). */
  fits: boolean | null;
  paths: number;
  /** mm of pen-down drawing. */
  drawLength_mm: number;
  /** mm of pen-up travel in the file's order, and as planned (merged and sorted). */
  travelBefore_mm: number;
  travelAfter_mm: number;
  /** s: planPath's duration of the job's moves from where the pen is now; null without a machine. */
  plotTime_s: number | null;
  /** µs: the link's floor on segment durations included in that time (0: none). */
  minSegment_us: number;
  /** Speeds above the machine's limits, said (they run at the limits). */
  notes: string[];
}

export type FileEvent =
  | { tool: 'plotter'; type: 'file-loaded'; summary: FileSummary; warnings: FileWarning[] }
  /**
   * `read`: the file was not loaded (the one before stays). `plan`: the loaded file
   * cannot be planned as the settings stand (bad settings, or a move the planner
   * refuses): its numbers no longer hold and Plot waits until a plan succeeds.
   */
  | { tool: 'plotter'; type: 'file-error'; stage: 'read' | 'plan'; name: string; message: string; line: number | null }
  | { tool: 'plotter'; type: 'file-preview'; layer: PreviewLayer; stats: PreviewStats }
  | { tool: 'plotter'; type: 'file-cleared' }
  /**
   * The file (`name`) is read or planned once the machine rests: real boards are
   * streamed from the worker, and the work would hold the stream back
   * (ToolContext.streamingToBoards).
   */
  | { tool: 'plotter'; type: 'file-waiting'; name: string }
  /** A plot started (`planned_s` the ETA's basis) or was refused (`reason`). */
  | { tool: 'plotter'; type: 'file-plot'; started: boolean; planned_s: number | null; reason: string | null };
