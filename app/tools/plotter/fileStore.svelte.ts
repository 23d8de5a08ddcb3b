/**
 * The page's side of the plotter's files: the settings the user edits, what the
 * worker said of the file (summary, warnings, error), its preview and plot time.
 * Commands go out as `file-*` with `tool: 'plotter'` (files/protocol.ts).
 */
import type { WorkbenchStore } from '../../lib/workbench.svelte.ts';
import { DEFAULT_ARRANGEMENT, type Arrangement } from './files/arrange.ts';
import { DEFAULT_CHORD_TOLERANCE_MM } from './files/flatten.ts';
import { DEFAULT_MERGE_TOLERANCE_MM } from './files/ordering.ts';
import type { FileWarning } from './files/paths.ts';
import type { PreviewLayer } from './files/previewLayer.ts';
import type { FileEvent, FileSummary, ImportSettings, PlotSettings, PreviewStats } from './files/protocol.ts';

export const DEFAULT_IMPORT: ImportSettings = { chordTolerance_mm: DEFAULT_CHORD_TOLERANCE_MM, gcodePen: 'auto', zThreshold_mm: 0 };

/**
 * The pen delays cover the Blot preset's servo (it lands in 120 ms and lifts in
 * 90 ms) with a margin; pen-down at a third of its 120 mm/s, travel at its top.
 */
export const DEFAULT_PLOT: PlotSettings = {
  arrangement: DEFAULT_ARRANGEMENT,
  merge: true,
  mergeTolerance_mm: DEFAULT_MERGE_TOLERANCE_MM,
  sort: true,
  drawSpeed: 40,
  travelSpeed: 120,
  penDelayDown_s: 0.15,
  penDelayUp_s: 0.12,
};

export class PlotterFileStore {
  summary = $state.raw<FileSummary | null>(null);
  warnings = $state.raw<FileWarning[]>([]);
  error = $state.raw<{ message: string; line: number | null; stage: 'read' | 'plan' } | null>(null);
  layer = $state.raw<PreviewLayer | null>(null);
  stats = $state.raw<PreviewStats | null>(null);
  plotResult = $state.raw<{ started: boolean; planned_s: number | null; reason: string | null } | null>(null);
  importSettings = $state<ImportSettings>({ ...DEFAULT_IMPORT });
  plotSettings = $state<PlotSettings>({ ...DEFAULT_PLOT, arrangement: { ...DEFAULT_ARRANGEMENT } });
  /**
   * What the worker is doing for the panel, said while it works (a file of 20 000
   * paths takes seconds to read, order and time): reading a file (its name), or
   * planning the one loaded; null when idle.
   */
  working = $state.raw<{ what: 'reading' | 'planning' | 'waiting'; name: string } | null>(null);
  private pendingArrangement: Arrangement | null = null;

  constructor(private readonly wb: WorkbenchStore) {
    wb.client.on((e) => {
      if (!('tool' in e) || e.tool !== 'plotter') return;
      this.onEvent(e as FileEvent);
    });
  }

  private onEvent(e: FileEvent): void {
    switch (e.type) {
      case 'file-loaded':
        if (this.pendingArrangement) this.plotSettings.arrangement = this.pendingArrangement;
        this.pendingArrangement = null;
        this.summary = e.summary;
        this.warnings = e.warnings;
        this.error = null;
        // Read; the worker orders and times it next.
        this.working = { what: 'planning', name: e.summary.name };
        break;
      case 'file-error':
        this.pendingArrangement = null;
        this.error = { message: e.message, line: e.line, stage: e.stage };
        // The loaded file's numbers no longer hold (its plot time was for other settings): none shown, no Plot.
        if (e.stage === 'plan') this.stats = null;
        this.working = null;
        break;
      case 'file-preview':
        this.layer = e.layer;
        this.stats = e.stats;
        // Planned: what stopped the plan before is gone (an error about another file that was not loaded stays).
        if (this.error?.stage === 'plan') this.error = null;
        this.working = null;
        break;
      case 'file-cleared':
        this.working = null;
        this.summary = null;
        this.warnings = [];
        this.layer = null;
        this.stats = null;
        this.error = null;
        break;
      case 'file-waiting':
        // Read and planned once the machine rests (real boards are streamed meanwhile).
        this.working = { what: 'waiting', name: e.name };
        break;
      case 'file-plot':
        this.plotResult = { started: e.started, planned_s: e.planned_s, reason: e.reason };
        break;
    }
  }

  async load(file: File): Promise<void> {
    this.working = { what: 'reading', name: file.name };
    this.plotResult = null;
    let text: string;
    try {
      text = await file.text();
    } catch (err) {
      this.working = null;
      this.error = { message: `“${file.name}” could not be read: ${(err as Error).message}`, line: null, stage: 'read' };
      return;
    }
    // A new file starts at true size, centred, or where its coordinates say for G-code;
    // the panel shows that arrangement once the worker has read the file (a bad file changes nothing).
    const gcode = !/\.svg$/i.test(file.name) && !/^\s*</.test(text);
    this.pendingArrangement = { ...DEFAULT_ARRANGEMENT, place: gcode ? 'file' : 'center' };
    this.wb.send({ tool: 'plotter', type: 'file-load', name: file.name, text, import: this.importNow(), plot: { ...this.plotNow(), arrangement: this.pendingArrangement } });
  }

  /** Sends the settings as they are now: the worker re-reads or re-plans. */
  update(): void {
    if (!this.summary) return;
    this.working = { what: 'planning', name: this.summary.name };
    this.wb.send({ tool: 'plotter', type: 'file-settings', import: this.importNow(), plot: this.plotNow() });
  }

  fit(): void {
    this.plotSettings.arrangement.fit = true;
    this.update();
  }

  plot(): void {
    this.plotResult = null;
    this.wb.send({ tool: 'plotter', type: 'file-plot' });
  }

  clear(): void {
    this.wb.send({ tool: 'plotter', type: 'file-clear' });
  }

  private importNow(): ImportSettings {
    return $state.snapshot(this.importSettings) as ImportSettings;
  }

  private plotNow(): PlotSettings {
    return $state.snapshot(this.plotSettings) as PlotSettings;
  }
}
