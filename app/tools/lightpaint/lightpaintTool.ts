/**
 * The light-painting tool in the worker: turns a bitmap and its settings into
 * the raster job (raster.ts) on the author, runs it through the job runner
 * (progress, ETA, pause, resume, cancel in the job panel), and, on a simulated
 * machine with an LED strip, sends the long exposure to the page a few times a
 * second while it changes.
 *
 * Nothing in the job is simulated-only: on real boards the same moves and event
 * channels drive the LightPainter example's NeoPixels.
 */
import { planPath, type LinearMove, type Maxl } from '../../../core/index.ts';
import type { ToolContext, WorkbenchTool } from '../../worker/toolContext.ts';
import { BitmapError, repeatBitmap, type Bitmap } from './bitmap.ts';
import { exposureFrame, fullScaleFor } from './exposureFrame.ts';
import { ledColour, parseHexColour } from './ledColour.ts';
import type { LightpaintCommand, PaintRequest } from './protocol.ts';
import { isProblem, planRaster } from './raster.ts';
import { rasterMachine } from './rasterMachine.ts';

/** ms between exposure frames while the strip is lit (and once after). */
const EXPOSURE_PERIOD_MS = 250;
const MAX_REPEAT = 50;

export class LightpaintTool implements WorkbenchTool<LightpaintCommand> {
  private lastSent = 0;
  /** The exposure changed since the last frame sent (the strip was lit). */
  private dirty = false;
  private fullScale = NaN;
  private lastSim: unknown = null;

  constructor(private readonly ctx: ToolContext) {}

  handle(cmd: LightpaintCommand): void {
    switch (cmd.type) {
      case 'paint':
        this.paint(cmd.request);
        break;
      case 'clear-exposure': {
        const leds = this.ctx.sim?.plant.leds;
        if (!leds) {
          this.ctx.log('warning', 'LIGHTPAINT', 'Only a simulated light painter has an exposure to clear.');
          return;
        }
        this.ctx.sim?.sync();
        leds.image.fill(0);
        leds.outside.fill(0);
        this.sendExposure(null);
        break;
      }
      case 'send-exposure':
        this.sendExposure(cmd.requestId);
        break;
    }
  }

  authorChanged(maxl: Maxl | null): void {
    void maxl;
    this.announceStrip();
  }

  stopped(): void {
    // The job runner says what the STOP dropped; the exposure keeps what was painted.
    this.dirty = true;
  }

  frame(): void {
    if (this.ctx.sim !== this.lastSim) this.announceStrip();
    const leds = this.ctx.sim?.plant.leds;
    if (!leds) return;
    const now = performance.now();
    if (now - this.lastSent < EXPOSURE_PERIOD_MS) return;
    this.ctx.sim?.sync();
    // Lit now, or lit since the last frame: one more frame shows the end of it.
    if (!leds.anyLit && !this.dirty) return;
    this.dirty = leds.anyLit;
    this.sendExposure(null);
  }

  private announceStrip(): void {
    const sim = this.ctx.sim;
    this.lastSim = sim;
    const strip = sim?.preset.plant.ledStrip?.strip;
    this.ctx.post({
      tool: 'lightpaint',
      type: 'strip',
      simulated: !!strip,
      ledCount: strip ? strip.count : null,
      ledSpacing_mm: strip ? Math.hypot(strip.pitch_mm[0], strip.pitch_mm[1]) : null,
    });
    if (strip) this.sendExposure(null);
  }

  private sendExposure(requestId: number | null): void {
    const sim = this.ctx.sim;
    const leds = sim?.plant.leds;
    if (!sim || !leds) {
      if (requestId !== null) this.ctx.log('warning', 'LIGHTPAINT', 'This machine has no simulated LED strip: there is no exposure to save.');
      return;
    }
    sim.sync();
    const { width, height, mmPerPixel, origin_mm } = leds.imageConfig;
    if (!(this.fullScale > 0)) {
      // Before any job: a lit (255, 60, 10) strip passing at the machine's top speed.
      const top = sim.config.limits?.maxVelocity;
      this.fullScale = fullScaleFor([255], mmPerPixel, typeof top === 'number' ? top : 100);
    }
    const frame = exposureFrame(leds.image, width, height, mmPerPixel, origin_mm, this.fullScale);
    this.lastSent = performance.now();
    this.ctx.post({ tool: 'lightpaint', type: 'exposure', requestId, ...frame }, [frame.rgba.buffer as ArrayBuffer]);
  }

  private paint(request: PaintRequest): void {
    const maxl = this.ctx.maxl;
    if (!maxl || this.ctx.phase !== 'ready') {
      this.problem('The machine is not ready: connect it (or pick a simulated one) and wait until it says ready.');
      return;
    }
    const s = request.settings;
    const rgb = parseHexColour(s.colour);
    if (!rgb) return this.problem(`“${s.colour}” is not a colour (#rrggbb).`);
    if (!(s.brightness > 0 && s.brightness <= 1)) return this.problem('Brightness must be between 1 and 100 %.');
    if (!(s.gamma >= 1 && s.gamma <= 4)) return this.problem('Gamma must be between 1 and 4.');
    const repeat = Math.round(s.repeat);
    if (!(repeat >= 1 && repeat <= MAX_REPEAT)) return this.problem(`Repeat must be a whole number from 1 to ${MAX_REPEAT}.`);
    if (request.width <= 0 || request.height <= 0 || request.lit.length !== request.width * request.height) {
      return this.problem('The picture is empty: type some text, paint some pixels, or load an image.');
    }
    let bitmap: Bitmap = { width: request.width, height: request.height, lit: request.lit };
    if (request.height > 8) return this.problem(`The picture is ${request.height} pixels tall; the strip's event track carries 8 LEDs.`);
    if (!bitmap.lit.some((v) => v === 1)) return this.problem('Nothing in the picture is lit: the strip would stay dark.');
    try {
      bitmap = repeatBitmap(bitmap, repeat);
    } catch (err) {
      if (err instanceof BitmapError) return this.problem(err.message);
      throw err;
    }
    const colour = ledColour(rgb, s.brightness, s.gamma);
    const plan = planRaster(
      bitmap,
      { speed: s.speed, pitch_mm: s.pitch_mm, colour, reverse: s.reverse, evaluationPrecision_ms: s.evaluationPrecision_ms, widthFixed: request.widthFixed === true },
      rasterMachine(maxl.config, this.ctx.origin),
    );
    if (isProblem(plan)) {
      this.ctx.post({ tool: 'lightpaint', type: 'problem', error: plan.error, fitPitch_mm: plan.fitPitch_mm });
      this.ctx.log('error', 'LIGHTPAINT', plan.error);
      return;
    }
    for (const note of plan.notes) this.ctx.log('warning', 'LIGHTPAINT', note);
    // The planner's own duration, for the job panel's ETA.
    const passes = plan.moves as LinearMove[];
    const planned_s = planPath(
      [...maxl.nextMoveStart],
      passes.map((m) => ({ end: m.endPosition as number[], maxVelocity: m.maxVelocity })),
      this.ctx.config.limits ?? {},
    ).duration;
    if (!this.ctx.startJob({ name: request.name, moves: plan.moves, planned_s })) {
      this.problem('The job did not start: see the log.');
      return;
    }
    const strip = this.ctx.sim?.preset.plant.ledStrip?.strip;
    const leds = this.ctx.sim?.plant.leds;
    if (leds) this.fullScale = fullScaleFor(colour, leds.imageConfig.mmPerPixel, plan.speed);
    this.ctx.post({
      tool: 'lightpaint',
      type: 'plan',
      layout: plan.layout,
      ledOffsets_mm: strip ? Array.from({ length: strip.count }, (_, k) => strip.origin_mm[1] + k * strip.pitch_mm[1]) : null,
      speed: plan.speed,
      cappedFrom: plan.cappedFrom,
      notes: plan.notes,
    });
    this.dirty = true;
  }

  private problem(error: string): void {
    this.ctx.post({ tool: 'lightpaint', type: 'problem', error });
    this.ctx.log('error', 'LIGHTPAINT', error);
  }
}
