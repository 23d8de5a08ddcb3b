/**
 * The light-painting tool on the page: its settings and input (kept while the
 * user switches tabs), what the worker said of the last job, and the exposure
 * frames, which go straight to the canvas that shows them (never reactive
 * state: a frame is 1.2 MB).
 */
import type { WorkbenchStore } from '../../lib/workbench.svelte.ts';
import type { Bitmap } from './bitmap.ts';
import type { ExposureFrame, LightpaintEvent, PaintSettings } from './protocol.ts';
import { DEFAULT_EVALUATION_PRECISION_MS, type RasterLayout } from './raster.ts';

export type Source = 'text' | 'paint' | 'image';

export interface PlanView {
  layout: RasterLayout;
  ledOffsets_mm: number[] | null;
  speed: number;
  cappedFrom: number | null;
  notes: string[];
}

export interface ExposureSink {
  show(frame: ExposureFrame, plan: PlanView | null): void;
}

/** LEDs on the LightPainter example's strip (and the 8-bit track). */
export const DEFAULT_LED_COUNT = 8;
/** mm between LEDs on a NeoPixel Stick, for an image's aspect on real boards. */
export const DEFAULT_LED_SPACING_MM = 6.4;

export class LightpaintStore {
  source: Source = $state('text');
  text = $state('HELLO');
  painted: Bitmap = $state.raw({ width: 24, height: DEFAULT_LED_COUNT, lit: new Uint8Array(24 * DEFAULT_LED_COUNT) });
  image: Bitmap | null = $state.raw(null);
  imageName = $state('');
  settings: PaintSettings = $state({
    speed: 100,
    pitch_mm: 2,
    colour: '#ffa040',
    brightness: 1,
    gamma: 2.2,
    reverse: false,
    repeat: 1,
    evaluationPrecision_ms: DEFAULT_EVALUATION_PRECISION_MS,
  });
  plan: PlanView | null = $state.raw(null);
  problem: { error: string; fitPitch_mm?: number } | null = $state.raw(null);
  simulated = $state(false);
  ledCount = $state(DEFAULT_LED_COUNT);
  ledSpacing_mm = $state(DEFAULT_LED_SPACING_MM);
  /** Exposure frames received (the e2e test waits on it). */
  frames = $state(0);
  private sink: ExposureSink | null = null;
  private lastFrame: ExposureFrame | null = null;
  private nextRequest = 1;
  private saves = new Map<number, (frame: ExposureFrame) => void>();

  constructor(private readonly wb: WorkbenchStore) {
    wb.client.on((e) => {
      if ('tool' in e && e.tool === 'lightpaint') this.onEvent(e);
    });
  }

  private onEvent(e: LightpaintEvent): void {
    switch (e.type) {
      case 'strip':
        this.simulated = e.simulated;
        if (e.ledCount !== null) this.ledCount = Math.min(8, e.ledCount);
        if (e.ledSpacing_mm !== null) this.ledSpacing_mm = e.ledSpacing_mm;
        break;
      case 'plan':
        this.plan = { layout: e.layout, ledOffsets_mm: e.ledOffsets_mm, speed: e.speed, cappedFrom: e.cappedFrom, notes: e.notes };
        this.problem = null;
        break;
      case 'problem':
        this.problem = { error: e.error, fitPitch_mm: e.fitPitch_mm };
        break;
      case 'exposure': {
        const frame: ExposureFrame = e;
        this.lastFrame = frame;
        this.frames++;
        this.sink?.show(frame, this.plan);
        if (e.requestId !== null) {
          this.saves.get(e.requestId)?.(frame);
          this.saves.delete(e.requestId);
        }
        break;
      }
    }
  }

  attach(sink: ExposureSink | null): void {
    this.sink = sink;
    if (sink && this.lastFrame) sink.show(this.lastFrame, this.plan);
  }

  /** `widthFixed`: an image, whose width in mm the pitch does not change (its aspect is kept). */
  paint(name: string, bitmap: Bitmap, widthFixed = false): void {
    this.problem = null;
    const lit = bitmap.lit.slice();
    this.wb.send(
      { tool: 'lightpaint', type: 'paint', request: { name, width: bitmap.width, height: bitmap.height, lit, settings: $state.snapshot(this.settings), widthFixed } },
      [lit.buffer],
    );
  }

  clearExposure(): void {
    this.wb.send({ tool: 'lightpaint', type: 'clear-exposure' });
  }

  /** The exposure as it is now, fresh from the worker. */
  freshExposure(): Promise<ExposureFrame> {
    const requestId = this.nextRequest++;
    return new Promise((resolve) => {
      this.saves.set(requestId, resolve);
      this.wb.send({ tool: 'lightpaint', type: 'send-exposure', requestId });
    });
  }

  note(message: string): void {
    this.problem = { error: message };
    this.wb.note('error', 'LIGHTPAINT', message);
  }
}
