/**
 * The plotter's page side: what the bed view draws and the panel shows, and the
 * commands it sends. It listens to the worker through the workbench's client.
 *
 * The strokes as drawn, their progress and the ink are plain arrays, not reactive
 * state (a stroke grows by hundreds of points a second): `version` ticks when they
 * change and the bed view redraws on its next animation frame.
 */
import { downloadText } from '../../lib/download.ts';
import type { WorkbenchStore } from '../../lib/workbench.svelte.ts';
import type { WorkerEvent } from '../../worker/protocol.ts';
import { DEFAULT_TOLERANCE_MM } from './penDefaults.ts';
import type { PenSettings } from './penSequence.ts';
import type { DrawStatus, DrawTruth, PlotterCommand } from './protocol.ts';

/** A stroke as the pointer drew it on the page. */
export interface PageStroke {
  id: number;
  /** x, y pairs, machine mm. */
  xy: number[];
  /** Index of the last point the machine has drawn to (-1: none); all of it once the stroke is complete. */
  done: number;
  /** Whether the worker refused it (nothing of it is drawn). */
  refused: boolean;
}

/** Strokes kept on the page for the view (the oldest go first). */
const STROKES_KEPT = 500;

export class PlotterStore {
  pen = $state.raw<PenSettings | null>(null);
  tolerance_mm = $state(DEFAULT_TOLERANCE_MM);
  status = $state.raw<DrawStatus | null>(null);
  /** Ticks whenever strokes, progress or ink change. */
  version = $state(0);
  strokes: PageStroke[] = [];
  /** The simulated pen's ink, x, y pairs per pen stroke. */
  ink: number[][] = [];
  /** The last stroke the worker refused, while no stroke has started since: the page says so beside the bed. */
  refused = $state.raw<{ id: number; reason: string; points: number } | null>(null);
  /** The import module's preview on the bed (IMPORT: set by the import panel): pen-down polylines and pen-up travel, x, y pairs. */
  preview = $state.raw<{ strokes: ArrayLike<number>[]; travel: ArrayLike<number>[] } | null>(null);
  private nextId = 1;
  private current: PageStroke | null = null;
  private pending: number[] = [];
  private truthWaiters: Array<(t: DrawTruth) => void> = [];

  constructor(private readonly wb: WorkbenchStore) {
    wb.client.on((e) => this.onEvent(e));
  }

  private send(cmd: PlotterCommand, transfer: Transferable[] = []): void {
    this.wb.send(cmd, transfer);
  }

  // --- the pointer ---

  /** The pointer went down at (x, y) mm; `t` is the event's epoch ms. */
  strokeStart(x: number, y: number, t: number): void {
    if (this.current) this.strokeEnd();
    this.refused = null;
    const s: PageStroke = { id: this.nextId++, xy: [x, y], done: -1, refused: false };
    this.current = s;
    this.strokes.push(s);
    if (this.strokes.length > STROKES_KEPT) this.strokes.splice(0, this.strokes.length - STROKES_KEPT);
    this.send({ tool: 'plotter', type: 'draw-start', id: s.id, x, y, t });
    this.version++;
  }

  /** A point of the stroke under way; sent with the others of its pointer event by flush(). */
  strokePoint(x: number, y: number, t: number): void {
    const s = this.current;
    if (!s) return;
    s.xy.push(x, y);
    this.pending.push(x, y, t);
  }

  /** Sends the points gathered since the last flush (one message per pointer event). */
  flush(): void {
    const s = this.current;
    if (!s || this.pending.length === 0) return;
    if (s.refused) {
      // Shown on the bed as not drawn, whole, as the hand drew it; nothing of it goes to the worker.
      this.pending = [];
      this.noteRefused(s);
      return;
    }
    const points = Float64Array.from(this.pending);
    this.pending = [];
    this.send({ tool: 'plotter', type: 'draw-points', id: s.id, points }, [points.buffer]);
    this.version++;
  }

  strokeEnd(): void {
    const s = this.current;
    if (!s) return;
    this.flush();
    this.current = null;
    if (!s.refused) this.send({ tool: 'plotter', type: 'draw-end', id: s.id });
  }

  private noteRefused(s: PageStroke): void {
    if (this.refused?.id === s.id) this.refused = { ...this.refused, points: s.xy.length / 2 };
    this.version++;
  }

  get drawing(): boolean {
    return this.current !== null;
  }

  // --- settings, files ---

  setPen(pen: Partial<PenSettings>, tolerance_mm?: number): void {
    this.send({ tool: 'plotter', type: 'pen-settings', pen, tolerance_mm });
  }

  clear(): void {
    this.send({ tool: 'plotter', type: 'draw-clear' });
  }

  save(kind: 'drawn' | 'planned'): void {
    this.send({ tool: 'plotter', type: 'draw-save', kind });
  }

  /** Dev/test hook (docs/test-hooks.md): the simulator's truth. Rejects in a production build. */
  truth(): Promise<DrawTruth> {
    if (!import.meta.env.DEV) return Promise.reject(new Error('draw-truth is a development hook'));
    return new Promise((resolve) => {
      this.truthWaiters.push(resolve);
      this.send({ tool: 'plotter', type: 'draw-truth' });
    });
  }

  // --- from the worker ---

  private onEvent(e: WorkerEvent): void {
    if (!('tool' in e) || e.tool !== 'plotter') return;
    switch (e.type) {
      case 'pen-settings':
        this.pen = e.pen;
        this.tolerance_mm = e.tolerance_mm;
        break;
      case 'draw-status':
        this.applyStatus(e.status);
        break;
      case 'stroke-refused': {
        // The stroke under way stays the pointer's: the rest of it is still shown (as not drawn), not sent.
        const s = this.strokes.find((x) => x.id === e.id);
        if (s) s.refused = true;
        this.refused = { id: e.id, reason: e.reason, points: s ? s.xy.length / 2 : 0 };
        this.version++;
        break;
      }
      case 'ink':
        for (const piece of e.pieces) {
          const line = (this.ink[piece.index] ??= []);
          line.length = piece.from * 2;
          for (let i = 0; i < piece.xy.length; i++) line.push(piece.xy[i]);
        }
        this.version++;
        break;
      case 'draw-cleared':
        this.ink = [];
        this.strokes = this.current ? [this.current] : [];
        this.version++;
        break;
      case 'draw-svg':
        downloadText(e.svg, `maxl-as-${e.kind}.svg`, 'image/svg+xml');
        this.wb.note('info', 'SAVED', `Saved ${e.strokes} stroke${e.strokes === 1 ? '' : 's'} as ${e.kind} (maxl-as-${e.kind}.svg).`);
        break;
      case 'draw-truth': {
        const waiters = this.truthWaiters;
        this.truthWaiters = [];
        for (const w of waiters) w(e.truth);
        break;
      }
    }
  }

  private applyStatus(status: DrawStatus): void {
    this.status = status;
    const live = new Map(status.strokes.map((s) => [s.id, s]));
    for (const s of this.strokes) {
      if (s.id > status.lastId) continue; // not taken yet
      const p = live.get(s.id);
      // A stroke the worker no longer lists is complete (or was never taken).
      s.done = p ? p.done : s.refused ? -1 : s.xy.length / 2 - 1;
    }
    this.version++;
  }
}
