/**
 * Paints a bitmap on a simulated machine in virtual time (core/system/harness.ts)
 * and hands back what the tests and the bench measure: where the bitmap lies,
 * the plant's exposure (its brightest channel) and the planned speed along the
 * pass. The job is the tool's own (planRaster), run on the real firmware in wasm.
 */
import { runJob, type Bench } from '../../../core/system/harness.ts';
import type { Bitmap } from './bitmap.ts';
import type { ExposureChannel } from './exposureAnalysis.ts';
import { isProblem, planRaster, type RasterLayout, type RasterPlan, type RasterSettings } from './raster.ts';
import { rasterMachine } from './rasterMachine.ts';

export interface Painting {
  plan: RasterPlan;
  layout: RasterLayout;
  /** The brightest channel of the colour, as an exposure image. */
  exposure: ExposureChannel;
  /** mm, each LED's y offset from the tool. */
  ledOffsets_mm: number[];
  /** mm/s planned where the tool passed x during the raster. */
  speedAt: (x: number) => number;
}

/**
 * The planned speed where the tool passed x, along the line y = `y` between
 * author times t0 and t1 (µs): the author's plan sampled every 0.1 ms while it
 * moved along x on that line, linear between samples. Where the tool passed x
 * more than once, the samples are mixed: use it on one pass.
 */
export function plannedSpeedAlong(b: Bench, y: number, t0: number, t1: number): (x: number) => number {
  const samples: Array<{ x: number; v: number }> = [];
  for (let t = t0; t <= t1; t += 100) {
    const s = b.maxl.sample(t);
    if (Math.abs(s.position[1] - y) < 1e-6 && Math.abs(s.velocity[1]) < 1e-9) samples.push({ x: s.position[0], v: s.speed });
  }
  samples.sort((a, c) => a.x - c.x);
  return (x) => {
    let lo = 0;
    let hi = samples.length - 1;
    if (hi < 0) return 0;
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (samples[mid].x <= x) lo = mid;
      else hi = mid;
    }
    const a = samples[lo];
    const c = samples[hi];
    return c.x === a.x ? Math.min(a.v, c.v) : a.v + ((c.v - a.v) * (x - a.x)) / (c.x - a.x);
  };
}

export async function paintOnSim(b: Bench, bitmap: Bitmap, settings: RasterSettings, origin: number[]): Promise<Painting> {
  const plan = planRaster(bitmap, settings, rasterMachine(b.maxl.config, origin));
  if (isProblem(plan)) throw new Error(plan.error);
  const leds = b.sim.plant.leds;
  const strip = b.sim.preset.plant.ledStrip;
  if (!leds || !strip) throw new Error('this machine has no LED strip');
  leds.image.fill(0);
  const { layout } = plan;
  const t0 = b.scheduler.now();
  await runJob(b, plan.moves);
  const speedAt = plannedSpeedAlong(b, layout.y, t0, b.scheduler.now());
  const { width, height, mmPerPixel, origin_mm } = leds.imageConfig;
  const brightest = settings.colour.indexOf(Math.max(...settings.colour));
  const values = new Float64Array(width * height);
  for (let k = 0; k < values.length; k++) values[k] = leds.image[3 * k + brightest];
  const ledOffsets_mm = Array.from({ length: strip.strip.count }, (_, k) => strip.strip.origin_mm[1] + k * strip.strip.pitch_mm[1]);
  return { plan, layout, exposure: { width, height, mmPerPixel, origin_mm, values }, ledOffsets_mm, speedAt };
}
