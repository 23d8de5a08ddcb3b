/**
 * The pen plotter's worker module (WorkbenchTool 'plotter'): routes the plotter's
 * commands by their type's prefix, keeps the pen settings, and posts to the page
 * what it draws on the bed view.
 *
 *   pen-*   the pen settings                 (here)
 *   draw-*  live drawing, and the saved files (live/liveDrawer.ts, live/plannedPen.ts, svg/strokesSvg.ts)
 *   file-*  SVG and G-code import, plotting  (files/fileJobs.ts)
 *
 * Each animation frame (frame()) it posts, only when something changed: the live
 * strokes' progress, and on a simulated machine the pen's new ink from the plant,
 * incrementally (only points not sent before) and at most every INK_PERIOD_MS,
 * in transferred Float32Arrays.
 */
import { PacedScheduler, type Maxl } from '../../../core/index.ts';
import type { ToolContext, WorkbenchTool } from '../../worker/toolContext.ts';
import { FileJobs } from './files/fileJobs.ts';
import type { FileCommand } from './files/protocol.ts';
import { LiveDrawer } from './live/liveDrawer.ts';
import { PlannedPen } from './live/plannedPen.ts';
import { PointerTimeline } from './live/pointerTimeline.ts';
import { SimulatedInk } from './live/simulatedInk.ts';
import { DEFAULT_TOLERANCE_MM, penDefaults, penSettingsProblem } from './penDefaults.ts';
import type { PenSettings } from './penSequence.ts';
import type { DrawTruth, PlotterCommand, PlotterEvent } from './protocol.ts';
import { strokesToSvg } from './svg/strokesSvg.ts';

/** Ink goes to the page at most this often, ms. */
const INK_PERIOD_MS = 50;

export class PlotterTool implements WorkbenchTool<PlotterCommand | FileCommand> {
  private pen: PenSettings | null = null;
  private tolerance_mm = DEFAULT_TOLERANCE_MM;
  /** The machine the settings were made for (its preset and config), to reset them when it changes. */
  private settingsFor = '';
  private readonly live: LiveDrawer;
  private readonly planned = new PlannedPen(() => this.pen);
  private statusChanged = true;
  private lastInk = 0;
  private readonly ink = new SimulatedInk();
  /** Pointer input, released at the author time it was made (live/pointerTimeline.ts). */
  private readonly pointer: PointerTimeline;
  /** Dev/test hook: each stroke's points on the author's clock, when each arrived, and how far the machine fell behind (docs/test-hooks.md). */
  private readonly received = new Map<number, { points: number[]; arrived: number[]; behindMax_mm: number; waitingMax: number }>();

  /** SVG and G-code files: import, preview, plot (files/). */
  private readonly files: FileJobs;

  constructor(private readonly ctx: ToolContext) {
    this.files = new FileJobs(ctx);
    this.pointer = new PointerTimeline(() => ctx.scheduler);
    this.live = new LiveDrawer({
      get maxl() {
        return ctx.maxl;
      },
      claim: (what) => ctx.claim('plotter', what),
      release: () => ctx.release('plotter'),
      log: (level, code, message) => ctx.log(level, code, message),
      strokeRefused: (id, reason) => this.post({ tool: 'plotter', type: 'stroke-refused', id, reason }),
    });
    this.live.onChange = () => (this.statusChanged = true);
  }

  handle(cmd: PlotterCommand | FileCommand): void {
    if (cmd.type.startsWith('file-')) this.files.handle(cmd as FileCommand);
    else if (cmd.type.startsWith('pen-')) this.handlePen(cmd as PlotterCommand);
    else if (cmd.type.startsWith('draw-')) this.handleDraw(cmd as PlotterCommand);
    else this.ctx.log('error', 'WORKER', `The plotter has no command "${(cmd as { type: string }).type}".`);
  }

  authorChanged(maxl: Maxl | null): void {
    this.pointer.clear();
    this.files.authorChanged(maxl);
    this.live.attach(maxl);
    this.planned.attach(maxl);
    this.resetSettingsIfMachineChanged();
    this.statusChanged = true;
  }

  stopped(): void {
    this.pointer.clear();
    this.live.stopped();
  }

  frame(): void {
    this.live.settle();
    this.files.frame();
    if (this.statusChanged) {
      this.statusChanged = false;
      this.post({ tool: 'plotter', type: 'draw-status', status: this.live.status() });
    }
    const now = performance.now();
    if (now - this.lastInk >= INK_PERIOD_MS) {
      this.lastInk = now;
      this.postInk();
    }
  }

  /** The pen settings now (defaults for this machine until edited); null if it has no pen channel. */
  settings(): PenSettings | null {
    this.resetSettingsIfMachineChanged();
    return this.pen;
  }

  // --- pen-* ---

  private handlePen(cmd: PlotterCommand): void {
    if (cmd.type !== 'pen-settings') return;
    const current = this.settings();
    if (!current) {
      this.ctx.log('warning', 'PEN', 'This machine has no event channel to drive a pen: add one in Configure, then set the pen.');
      this.postSettings();
      return;
    }
    const next: PenSettings = { ...current, ...cmd.pen };
    const tolerance = cmd.tolerance_mm ?? this.tolerance_mm;
    const problem = penSettingsProblem(next, this.machine()) ?? (Number.isFinite(tolerance) && tolerance >= 0 && tolerance <= 10 ? null : `the thinning tolerance must be between 0 and 10 mm, got ${tolerance}`);
    if (problem) {
      this.ctx.log('error', 'PEN', `Pen settings not changed: ${problem}.`);
      this.postSettings();
      return;
    }
    const limit = this.machine().limits.maxVelocity;
    for (const [name, v] of [['draw', next.drawSpeed], ['travel', next.travelSpeed]] as const) {
      if (v > limit) this.ctx.log('info', 'PEN', `The ${name} speed ${v} mm/s is above the machine's limit: it runs at ${limit} mm/s.`);
    }
    this.pen = next;
    this.tolerance_mm = tolerance;
    this.postSettings();
  }

  private machine() {
    const c = this.ctx.config;
    return { motionAxes: c.motionAxes, eventChannels: c.eventChannels, limits: { maxVelocity: scalarLimit(c.limits.maxVelocity) } };
  }

  private resetSettingsIfMachineChanged(): void {
    const c = this.ctx.config;
    const key = JSON.stringify([this.ctx.presetId, c.motionAxes, c.eventChannels ?? [], c.limits.maxVelocity ?? null]);
    if (key === this.settingsFor) return;
    this.settingsFor = key;
    this.pen = penDefaults(this.machine(), this.ctx.presetId);
    this.postSettings();
  }

  private postSettings(): void {
    if (this.pen) this.post({ tool: 'plotter', type: 'pen-settings', pen: this.pen, tolerance_mm: this.tolerance_mm });
  }

  // --- draw-* ---

  private handleDraw(cmd: PlotterCommand): void {
    switch (cmd.type) {
      case 'draw-start': {
        const t = this.authorTime(cmd.t);
        this.pointer.push(t, () => {
          if (import.meta.env.DEV) this.received.set(cmd.id, { points: [cmd.x, cmd.y, t], arrived: [this.ctx.scheduler.now()], behindMax_mm: 0, waitingMax: 0 });
          if (!this.live.start(cmd.id, [cmd.x, cmd.y], this.settings(), this.tolerance_mm)) this.received.delete(cmd.id);
          this.statusChanged = true;
        });
        return;
      }
      case 'draw-points': {
        const p = cmd.points;
        for (let i = 0; i + 2 < p.length; i += 3) {
          const [x, y, t] = [p[i], p[i + 1], this.authorTime(p[i + 2])];
          this.pointer.push(t, () => this.takePoint(cmd.id, x, y, t));
        }
        return;
      }
      case 'draw-end':
        this.pointer.push(NaN, () => {
          this.live.end(cmd.id);
          this.statusChanged = true;
        });
        return;
      case 'draw-clear':
        this.received.clear();
        this.planned.clear();
        this.ink.clear();
        this.post({ tool: 'plotter', type: 'draw-cleared' });
        return;
      case 'draw-save':
        this.save(cmd.kind);
        return;
      case 'draw-truth':
        if (import.meta.env.DEV) this.post({ tool: 'plotter', type: 'draw-truth', truth: this.truth() });
        else this.ctx.log('error', 'WORKER', 'draw-truth is a development hook: this build has none.');
        return;
    }
  }

  /** One pointer point, at the author time it was made (`t`, µs). */
  private takePoint(id: number, x: number, y: number, t: number): void {
    this.live.points(id, [x, y]);
    const record = import.meta.env.DEV ? this.received.get(id) : undefined;
    if (record) {
      record.points.push(x, y, t);
      record.arrived.push(this.ctx.scheduler.now());
      const status = this.live.status();
      record.behindMax_mm = Math.max(record.behindMax_mm, status.behind_mm);
      record.waitingMax = Math.max(record.waitingMax, status.waitingMoves);
    }
    this.statusChanged = true;
  }

  /** Author µs of a pointer event at epoch ms `t`: exact on a paced (simulated) machine, else by the wall clock now. */
  private authorTime(t: number): number {
    const s = this.ctx.scheduler;
    const wall_us = (t - performance.timeOrigin) * 1000;
    if (s instanceof PacedScheduler) return s.virtualTimeAtWall(wall_us);
    return s.now() - (performance.now() * 1000 - wall_us);
  }

  private postInk(): void {
    if (this.ink.follow(this.ctx.sim)) {
      this.planned.clear();
      this.post({ tool: 'plotter', type: 'draw-cleared' });
    }
    const pieces = this.ink.newPieces();
    if (pieces.length > 0) this.post({ tool: 'plotter', type: 'ink', pieces }, pieces.map((p) => p.xy.buffer));
  }

  private save(kind: 'drawn' | 'planned'): void {
    const c = this.ctx.maxl?.config;
    const pen = this.pen;
    const axes = pen ? pen.axes.map((a) => this.ctx.config.motionAxes.indexOf(a)) : [0, 1];
    const lo = c ? axes.map((a) => c.softMin[a]) : [0, 0];
    const hi = c ? axes.map((a) => c.softMax[a]) : [0, 0];
    let strokes: number[][];
    let title: string;
    if (kind === 'planned') {
      strokes = this.planned.strokes;
      title = 'MAXL plotter: the pen-down path as planned';
    } else {
      const ink = this.ink.strokes();
      // A real board reports no ink: the pen-down path sent to it (the planned file's) is the best record there is.
      strokes = ink ?? this.planned.strokes;
      title = ink ? 'MAXL plotter: the simulated pen’s ink (as drawn)' : 'MAXL plotter: the pen-down path sent to the machine (a real board reports no ink)';
    }
    // The page: the soft limits if bounded, else the drawing's own bounds.
    const page = pageOf(lo, hi, strokes);
    const svg = strokesToSvg(strokes, { page, title });
    this.post({ tool: 'plotter', type: 'draw-svg', kind, svg, strokes: strokes.length });
  }

  private truth(): DrawTruth {
    const ink = this.ink.strokes(true) ?? [];
    const maxl = this.ctx.maxl;
    const status = this.live.status();
    return {
      ink,
      strokes: [...this.received].map(([id, r]) => ({ id, ...r })),
      now_us: this.ctx.scheduler.now(),
      lead_us: maxl?.lead_us ?? NaN,
      limits: { maxVelocity: scalarLimit(this.ctx.config.limits.maxVelocity), maxAcceleration: scalarLimit(this.ctx.config.limits.maxAcceleration) },
      tolerance_mm: this.tolerance_mm,
      refusedPoints: this.live.refusedPoints,
      fedMoves: this.live.fedMoves,
      waitingMoves: status.waitingMoves,
      paced: this.ctx.scheduler instanceof PacedScheduler,
      stalls: this.ctx.scheduler instanceof PacedScheduler ? this.ctx.scheduler.stalls : [],
    };
  }

  private post(e: PlotterEvent, transfer?: Transferable[]): void {
    this.ctx.post(e, transfer);
  }
}

/** A limit given as one number or per axis, as one number (the smallest: the pen's path may run along any axis). */
function scalarLimit(v: number | number[] | undefined): number {
  if (v === undefined) return Infinity;
  return Array.isArray(v) ? Math.min(...v) : v;
}

function pageOf(lo: number[], hi: number[], strokes: readonly number[][]): [number, number, number, number] {
  if (lo.every(Number.isFinite) && hi.every(Number.isFinite) && hi[0] > lo[0] && hi[1] > lo[1]) return [lo[0], lo[1], hi[0], hi[1]];
  let [x0, y0, x1, y1] = [Infinity, Infinity, -Infinity, -Infinity];
  for (const s of strokes) {
    for (let i = 0; i + 1 < s.length; i += 2) {
      x0 = Math.min(x0, s[i]);
      x1 = Math.max(x1, s[i]);
      y0 = Math.min(y0, s[i + 1]);
      y1 = Math.max(y1, s[i + 1]);
    }
  }
  return Number.isFinite(x0) ? [x0 - 1, y0 - 1, x1 + 1, y1 + 1] : [0, 0, 100, 100];
}
