/**
 * The plotter's files in the worker: reads an SVG or G-code file, places it on the
 * bed, orders its paths, times the plot with the planner, and plots it as a job.
 *
 *   file-load      read the file (a bad one is refused whole; the one before stays)
 *   file-settings  re-read (import settings) and/or re-plan (plot settings)
 *   file-plot      the job: re-planned from where the pen is now, then ctx.startJob
 *   file-clear     forget the file
 *
 * Reading and planning run on the worker's thread, which also streams real boards:
 * a big file (20 000 paths) holds it for a second, and a job running on the boards
 * meanwhile would starve and brake to rest. So while the boards are streamed
 * (ToolContext.streamingToBoards) a load or a change of settings waits, said with
 * `file-waiting`, and runs at the first frame after the machine rests; a newer one
 * replaces it.
 *
 * Each plan posts `file-preview`: the strokes and travel in machine mm, the travel
 * before and after ordering, and the exact plot time (plotJob.ts).
 */
import { batchItemOf, isMoveError, MaxlError, type LimitsConfig, type Maxl, type Move } from '../../../../core/index.ts';
import { jobMoveError } from '../../../worker/jobMoveError.ts';
import type { ToolContext, WorkbenchTool } from '../../../worker/toolContext.ts';
import type { PenSettings } from '../penSequence.ts';
import { arrange, type Area } from './arrange.ts';
import { importGcode } from './gcodeImport.ts';
import { mergePaths, sortPaths } from './ordering.ts';
import { boundsOf, FileImportError, lineOfSegment, pathLength, travelLength, type Drawing, type PlotPath } from './paths.ts';
import { describeSource, plotJobMoves, plotTime, type MoveSource } from './plotJob.ts';
import { layerBuffers, packLines, travelLines, type PreviewLayer } from './previewLayer.ts';
import type { FileCommand, FileEvent, FileKind, ImportSettings, PlotSettings, PreviewStats } from './protocol.ts';
import { settingsProblems } from './settingsCheck.ts';
import { importSvg } from './svgImport.ts';

/** The plan of the current file on the current machine. */
interface Plan {
  /** Machine mm, in plotting order. */
  paths: PlotPath[];
  /** The job's moves, which the plot time was planned over. */
  moves: Move[];
  /** Where each move comes from (its path in `paths`, its segment), for the user's words if one is refused. */
  sources: MoveSource[];
  stats: PreviewStats;
  layer: PreviewLayer;
}

export function fileKind(name: string, text: string): FileKind {
  if (/\.svg$/i.test(name)) return 'svg';
  if (/\.(g|gc|gco|gcode|nc|ngc|tap)$/i.test(name)) return 'gcode';
  return /^\s*(<\?xml|<svg|<!DOCTYPE svg|<!--)/i.test(text) ? 'svg' : 'gcode';
}

/** mm/s: the machine's top speed along any line (the smallest bound when limits are per axis). */
export function topSpeed(limits: LimitsConfig): number {
  const v = limits.maxVelocity;
  const all = [...(typeof v === 'number' ? [v] : Array.isArray(v) ? v : []), ...(limits.axisMaxVelocity ?? [])];
  return all.length > 0 ? Math.min(...all) : Infinity;
}

export class FileJobs implements WorkbenchTool<FileCommand> {
  private text = '';
  private drawing: Drawing | null = null;
  private importSettings: ImportSettings | null = null;
  private plotSettings: PlotSettings | null = null;
  private plan: Plan | null = null;
  /** What is wrong with the settings last given (settingsCheck.ts); no plan while there is something. */
  private settingsProblem: string | null = null;
  /** A load or a change of settings waiting for the boards' stream to end (see the module comment). */
  private waiting: Extract<FileCommand, { type: 'file-load' | 'file-settings' }> | null = null;

  constructor(private readonly ctx: ToolContext) {}

  handle(cmd: FileCommand): void {
    if ((cmd.type === 'file-load' || cmd.type === 'file-settings') && (this.waiting || this.ctx.streamingToBoards)) {
      this.wait(cmd);
      return;
    }
    switch (cmd.type) {
      case 'file-load':
        this.load(cmd.name, cmd.text, cmd.import, cmd.plot);
        return;
      case 'file-settings': {
        // Bad settings: said, and no plan (nor plot) until they are fixed; the drawing stays as read.
        this.plotSettings = cmd.plot;
        if (this.refusedSettings(cmd.import, cmd.plot)) return;
        const reread = this.drawing !== null && JSON.stringify(cmd.import) !== JSON.stringify(this.importSettings);
        if (reread && this.drawing) {
          if (!this.read(this.drawing.name, this.text, cmd.import)) return;
        }
        this.importSettings = cmd.import;
        this.plotSettings = cmd.plot;
        this.replan();
        return;
      }
      case 'file-plot':
        this.plot();
        return;
      case 'file-clear':
        this.waiting = null;
        this.text = '';
        this.drawing = null;
        this.plan = null;
        this.post({ tool: 'plotter', type: 'file-cleared' });
        return;
    }
  }

  /**
   * A new author (or none), perhaps with a new configuration: the plot time depends
   * on its position, limits and links, and a G-code file's feeds on its top speed.
   */
  authorChanged(_maxl: Maxl | null): void {
    if (!this.drawing) return;
    if (this.drawing.kind === 'gcode' && this.importSettings) this.read(this.drawing.name, this.text, this.importSettings);
    this.replan();
  }

  /** STOP: a running plot is the job runner's, which halts it; nothing waits here. */
  stopped(): void {}

  /** Runs the load or change of settings that waited, once the boards' stream has ended. */
  frame(): void {
    const cmd = this.waiting;
    if (!cmd || this.ctx.streamingToBoards) return;
    this.waiting = null;
    this.handle(cmd);
  }

  /** Keeps `cmd` for when the stream ends, and says so: settings changed after a waiting load go with that load. */
  private wait(cmd: Extract<FileCommand, { type: 'file-load' | 'file-settings' }>): void {
    const before = this.waiting;
    this.waiting = cmd.type === 'file-settings' && before?.type === 'file-load' ? { ...before, import: cmd.import, plot: cmd.plot } : cmd;
    const name = this.waiting.type === 'file-load' ? this.waiting.name : (this.drawing?.name ?? '');
    this.post({ tool: 'plotter', type: 'file-waiting', name });
  }

  /** Checks the settings; if something is wrong, says what, drops the plan and returns true. */
  private refusedSettings(imp: ImportSettings, plot: PlotSettings): boolean {
    const problems = settingsProblems(imp, plot);
    this.settingsProblem = problems.length > 0 ? problems.join(' ') : null;
    if (!this.settingsProblem) return false;
    this.plan = null;
    const name = this.drawing?.name ?? '';
    this.post({ tool: 'plotter', type: 'file-error', stage: 'plan', name, message: `${name ? `“${name}” cannot be planned: ` : ''}${this.settingsProblem}`, line: null });
    return true;
  }

  private load(name: string, text: string, imp: ImportSettings, plot: PlotSettings): void {
    const problems = settingsProblems(imp, plot);
    if (problems.length > 0) {
      this.post({ tool: 'plotter', type: 'file-error', stage: 'read', name, message: `“${name}” was not loaded: ${problems.join(' ')}`, line: null });
      return;
    }
    this.settingsProblem = null;
    const prevText = this.text;
    this.text = text;
    if (!this.read(name, text, imp)) {
      this.text = prevText;
      return;
    }
    this.importSettings = imp;
    this.plotSettings = plot;
    this.replan();
  }

  /** Reads the file; on success it replaces the drawing and says so, else it says why and changes nothing. */
  private read(name: string, text: string, imp: ImportSettings): boolean {
    let drawing: Drawing;
    try {
      const kind = fileKind(name, text);
      drawing =
        kind === 'svg'
          ? importSvg(name, text, { chordTolerance_mm: imp.chordTolerance_mm })
          : importGcode(name, text, { chordTolerance_mm: imp.chordTolerance_mm, pen: imp.gcodePen, zThreshold_mm: imp.zThreshold_mm, maxSpeed_mm_s: topSpeed(this.ctx.config.limits) });
    } catch (err) {
      if (!(err instanceof FileImportError)) throw err;
      const message = `“${name}” was not loaded: ${err.message}`;
      this.ctx.log('error', 'FILE_INVALID', message);
      this.post({ tool: 'plotter', type: 'file-error', stage: 'read', name, message, line: err.line ?? null });
      return false;
    }
    this.drawing = drawing;
    const b = boundsOf(drawing.paths);
    let points = 0;
    for (const p of drawing.paths) points += p.points.length / 2;
    this.post({
      tool: 'plotter',
      type: 'file-loaded',
      summary: { name, kind: drawing.kind, paths: drawing.paths.length, points, width_mm: b ? b.maxX - b.minX : 0, height_mm: b ? b.maxY - b.minY : 0 },
      warnings: drawing.warnings,
    });
    this.ctx.log(
      drawing.warnings.length > 0 ? 'warning' : 'info',
      'FILE',
      `“${name}”: ${drawing.paths.length} paths${drawing.warnings.length > 0 ? `; ${drawing.warnings.length} warnings (see the plotter's file panel)` : ''}.`,
    );
    return true;
  }

  private penSettings(notes: string[]): PenSettings | string {
    const c = this.ctx.config;
    const s = this.plotSettings as PlotSettings;
    if (c.motionAxes.length < 2) return `the machine has ${c.motionAxes.length} motion axis; a plotter needs two (x and y)`;
    const channels = c.eventChannels ?? [];
    const channel = channels.includes('pen') ? 'pen' : channels[0];
    if (channel === undefined) return 'the machine has no event channel to drive the pen (Configure → Tracks)';
    const top = topSpeed(c.limits);
    for (const [what, v] of [
      ['pen-down', s.drawSpeed],
      ['travel', s.travelSpeed],
    ] as const) {
      if (v > top) notes.push(`The ${what} speed ${v} mm/s is above the machine's ${top} mm/s: it runs at ${top} mm/s.`);
    }
    return {
      channel,
      up: 0,
      down: 1,
      delayUp_s: s.penDelayUp_s,
      delayDown_s: s.penDelayDown_s,
      drawSpeed: s.drawSpeed,
      travelSpeed: s.travelSpeed,
      axes: [c.motionAxes[0], c.motionAxes[1]],
    };
  }

  private area(): Area | null {
    const c = this.ctx.config;
    const x = c.softLimits?.[c.motionAxes[0]];
    const y = c.softLimits?.[c.motionAxes[1]];
    return x && y ? { minX: x[0], maxX: x[1], minY: y[0], maxY: y[1] } : null;
  }

  /** mm: where the pen is now (or the work origin without a machine). */
  private start(): number[] {
    return [...(this.ctx.maxl?.nextMoveStart ?? this.ctx.origin)];
  }

  /** Plans the current file with the current settings and posts the preview; null (with a message) if it cannot. */
  private replan(): Plan | null {
    this.plan = null;
    const d = this.drawing, s = this.plotSettings;
    if (!d || !s || this.settingsProblem) return null;
    const notes: string[] = [];
    const pen = this.penSettings(notes);
    if (typeof pen === 'string') {
      this.post({ tool: 'plotter', type: 'file-error', stage: 'plan', name: d.name, message: `“${d.name}” cannot be plotted here: ${pen}.`, line: null });
      return null;
    }
    const start = this.start();
    const from: [number, number] = [start[0], start[1]];
    const area = this.area();
    const placed = arrange(d.paths, s.arrangement, area, [this.ctx.origin[0] ?? 0, this.ctx.origin[1] ?? 0]);
    const fileOrder = placed.paths;
    let ordered = s.merge ? mergePaths(fileOrder, s.mergeTolerance_mm) : fileOrder;
    if (s.sort) ordered = sortPaths(ordered, from);
    const sources: MoveSource[] = [];
    const moves = plotJobMoves(ordered, pen, sources);
    const maxl = this.ctx.maxl;
    let plotTime_s: number | null = null;
    let minSegment_us = 0;
    if (maxl) {
      minSegment_us = maxl.feedLimit?.minSegment_us ?? 0;
      try {
        plotTime_s = plotTime(moves, this.ctx.config.motionAxes, start, this.ctx.config.limits, minSegment_us);
      } catch (err) {
        // A move the planner refuses (a G-code F too slow for it…): said with the line of the file it comes from.
        if (!(err instanceof MaxlError) || !isMoveError(err)) throw err;
        const index = batchItemOf(err)?.index ?? -1;
        const source = sources[index];
        const message = `“${d.name}” cannot be plotted: ${jobMoveError(err, index, describeSource(ordered, source)).message}`;
        this.ctx.log('error', 'FILE_INVALID', message);
        const line = source && source.path >= 0 ? lineOfSegment(ordered[source.path], source.segment) : null;
        this.post({ tool: 'plotter', type: 'file-error', stage: 'plan', name: d.name, message, line });
        return null;
      }
    }
    let drawLength_mm = 0;
    for (const p of ordered) drawLength_mm += pathLength(p);
    if (placed.fits === false) {
      const fit = placed.fitScale !== null ? ` Fit scales it by ${placed.fitScale.toFixed(3)}.` : '';
      notes.push(`The drawing (${(placed.bounds.maxX - placed.bounds.minX).toFixed(1)} × ${(placed.bounds.maxY - placed.bounds.minY).toFixed(1)} mm here) leaves the bed's soft limits: fit it, scale it down or move it; nothing is clipped.${fit}`);
    }
    const stats: PreviewStats = {
      scale: placed.scale,
      fitScale: placed.fitScale,
      width_mm: placed.bounds.maxX - placed.bounds.minX,
      height_mm: placed.bounds.maxY - placed.bounds.minY,
      fits: placed.fits,
      paths: ordered.length,
      drawLength_mm,
      travelBefore_mm: travelLength(fileOrder, from),
      travelAfter_mm: travelLength(ordered, from),
      plotTime_s,
      minSegment_us,
      notes,
    };
    const layer: PreviewLayer = {
      strokes: packLines(ordered),
      travel: travelLines(ordered, from),
      travelBefore: travelLines(fileOrder, from),
      area,
    };
    this.plan = { paths: ordered, moves, sources, stats, layer };
    this.post({ tool: 'plotter', type: 'file-preview', layer, stats }, layerBuffers(layer));
    return this.plan;
  }

  private plot(): void {
    const refuse = (reason: string) => {
      this.ctx.log('error', 'FILE_PLOT', reason);
      this.post({ tool: 'plotter', type: 'file-plot', started: false, planned_s: null, reason });
    };
    if (!this.drawing) return refuse('There is no file to plot: open an SVG or G-code file first.');
    const maxl = this.ctx.maxl;
    if (!maxl) return refuse('There is no machine to plot on.');
    if (this.settingsProblem) return refuse(`“${this.drawing.name}” cannot be planned: ${this.settingsProblem}`);
    // Planned afresh from where the pen is now, so that the ETA is the plan's own time.
    const plan = this.replan();
    if (!plan) return refuse(`“${this.drawing.name}” cannot be plotted on this machine.`);
    if (plan.stats.fits === false) return refuse(`“${this.drawing.name}” leaves the bed's soft limits: fit it (or scale it down) first; nothing is clipped.`);
    const moves = plan.moves;
    const planned_s = plan.stats.plotTime_s ?? undefined;
    const describeMove = (i: number) => describeSource(plan.paths, plan.sources[i]);
    const started = this.ctx.startJob({ name: this.drawing.name, moves, planned_s, describeMove });
    this.post({
      tool: 'plotter',
      type: 'file-plot',
      started,
      planned_s: planned_s ?? null,
      reason: started ? null : 'the job did not start: see the log',
    });
  }

  private post(e: FileEvent, transfer?: Transferable[]): void {
    this.ctx.post(e, transfer);
  }
}
