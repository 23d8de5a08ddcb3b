/**
 * The light-painting job on the simulated light painter (real LightPainter and
 * Stepper firmware in wasm, CoreXY plant with its springy tool), in virtual
 * time: every column lands within a quarter pitch at 100 and 200 mm/s, ramps
 * included, and an all-lit bar gets even light per mm through the ramps.
 */
import { describe, expect, it } from 'vitest';
import { lightPainter } from '../../../core/sim/presets/index.ts';
import { settle, startMachine } from '../../../core/system/harness.ts';
import { emptyBitmap, textBitmap } from './bitmap.ts';
import { analyseColumns, exposureEvenness } from './exposureAnalysis.ts';
import { ledColour } from './ledColour.ts';
import { DEFAULT_EVALUATION_PRECISION_MS, isProblem, planRaster, type RasterSettings } from './raster.ts';
import { rasterMachine } from './rasterMachine.ts';
import { paintOnSim, plannedSpeedAlong } from './simPainting.ts';

const PITCH = 2;
const settings = (speed: number): RasterSettings => ({
  speed,
  pitch_mm: PITCH,
  colour: ledColour([255, 160, 64], 1, 2.2),
  reverse: false,
  evaluationPrecision_ms: DEFAULT_EVALUATION_PRECISION_MS,
});

describe('light painting on the simulated light painter', () => {
  for (const speed of [100, 200]) {
    it(`puts every column of a word within a quarter pitch at ${speed} mm/s, ramps included`, async () => {
      const b = await startMachine(lightPainter());
      // Short enough that part of the word is drawn while accelerating and braking.
      const word = textBitmap('MAXL', 8);
      const painting = await paintOnSim(b, word, settings(speed), [20, 100]);
      const a = analyseColumns(painting.exposure, painting.layout, painting.ledOffsets_mm);

      expect(a.mismatches).toEqual([]);
      expect(a.placementError_mm).toBeLessThanOrEqual(PITCH / 4);
      // Some columns were drawn on the ramps (the word is shorter than the speed takes to reach).
      const ramped = painting.layout.bits.filter((_, c) => painting.speedAt(painting.layout.x0 + (c + 0.5) * PITCH) < 0.99 * painting.plan.speed);
      expect(ramped.length).toBeGreaterThan(0);
      await b.sim.stop();
    }, 120_000);

    it(`keeps light per mm within ±10 % of cruise through the ramps at ${speed} mm/s`, async () => {
      const b = await startMachine(lightPainter());
      const bar = emptyBitmap(60, 8);
      bar.lit.fill(1);
      const painting = await paintOnSim(b, bar, settings(speed), [20, 100]);
      const e = exposureEvenness(painting.exposure, painting.layout, painting.ledOffsets_mm, painting.speedAt, painting.plan.speed);

      expect(e.rampBins).toBeGreaterThan(3);
      expect(e.cruiseBins).toBeGreaterThan(3);
      expect(e.rampSpread).toBeLessThanOrEqual(0.1);
      await b.sim.stop();
    }, 120_000);
  }

  it('right to left, the word lands in the same place', async () => {
    const b = await startMachine(lightPainter(), { seed: 5 });
    const painting = await paintOnSim(b, textBitmap('MAXL', 8), { ...settings(200), reverse: true }, [20, 100]);
    const a = analyseColumns(painting.exposure, painting.layout, painting.ledOffsets_mm);
    expect(a.mismatches).toEqual([]);
    expect(a.placementError_mm).toBeLessThanOrEqual(PITCH / 4);
    await b.sim.stop();
  }, 120_000);

  it('without the cruise channel the strip is not dimmed, and the ramps get far more light per mm', async () => {
    const preset = lightPainter();
    preset.config.eventChannels = preset.config.eventChannels!.filter((c) => c !== 'neopixelCruise');
    preset.config.subscriptions = preset.config.subscriptions!.filter((sub) => sub.track !== 'neopixelCruise');
    const b = await startMachine(preset);
    const bar = emptyBitmap(60, 8);
    bar.lit.fill(1);
    const painting = await paintOnSim(b, bar, settings(200), [20, 100]);
    expect(painting.plan.notes.join(' ')).toMatch(/not dimmed/);
    const e = exposureEvenness(painting.exposure, painting.layout, painting.ledOffsets_mm, painting.speedAt, painting.plan.speed);
    // At 20 % of cruise an undimmed strip leaves 5 times the light per mm.
    expect(e.rampSpread).toBeGreaterThan(1);
    await b.sim.stop();
  }, 120_000);
});

describe('pausing mid-pass', () => {
  it('leaves no blob: at rest the strip is dark (v = 0), and light per mm stays even through the stop and the restart', async () => {
    const b = await startMachine(lightPainter());
    const bar = emptyBitmap(60, 8);
    bar.lit.fill(1);
    const speed = 100;
    const plan = planRaster(bar, settings(speed), rasterMachine(b.maxl.config, [20, 100]));
    if (isProblem(plan)) throw new Error(plan.error);
    const leds = b.sim.plant.leds!;
    leds.image.fill(0);
    const start = b.scheduler.now();
    for (const m of plan.moves) await settle(b.scheduler, b.maxl.addSegmentToQueue(m), 1_000_000);
    // Run until the tool is in the middle of the bar, then pause there for a second.
    const middle = plan.layout.x0 + 60;
    const deadline = b.scheduler.now() + 10_000_000;
    const tool = () => {
      b.sim.sync();
      return b.sim.plant.toolXY();
    };
    while (!(tool()[0] >= middle && Math.abs(tool()[1] - 100) < 0.1)) {
      if (b.scheduler.now() > deadline) throw new Error('the pass never reached the middle');
      await b.scheduler.advance(1000);
    }
    await settle(b.scheduler, b.maxl.pause(), 2_000_000);
    const stoppedAt = tool()[0];
    b.sim.sync();
    const atRest = Float32Array.from(leds.image);
    await b.scheduler.advance(1_000_000);
    b.sim.sync();
    // Nothing was added while the machine stood still with a lit column under it.
    let added = 0;
    for (let k = 0; k < atRest.length; k++) added = Math.max(added, leds.image[k] - atRest[k]);
    expect(added).toBeLessThan(1e-3);
    b.maxl.resume();
    await b.scheduler.runWhile(() => b.maxl.queue.untransmittedCount > 0 || b.maxl.queue.transmittedEnd_us > b.scheduler.now() - 2000, b.scheduler.now() + 10_000_000);
    b.sim.sync();
    const { width, height, mmPerPixel, origin_mm } = leds.imageConfig;
    const values = new Float64Array(width * height);
    for (let k = 0; k < values.length; k++) values[k] = leds.image[3 * k];
    const offsets = Array.from({ length: 8 }, (_, k) => -22.4 + 6.4 * k);
    const speedAt = plannedSpeedAlong(b, 100, start, b.scheduler.now());
    // It did stop in the bar: the planned speed falls to rest near the middle.
    let slowest = Infinity;
    // (within a step and the belt's give of where the plan rests; v = √(2·a·d) so a fine grid)
    for (let x = stoppedAt - 0.1; x <= stoppedAt + 0.1; x += 1e-4) slowest = Math.min(slowest, speedAt(x));
    expect(slowest).toBeLessThan(1);
    expect(Math.abs(stoppedAt - middle)).toBeLessThan(10);
    // Around the stop the planned speed falls to 0 and rises again: those bins are ramps too.
    const e = exposureEvenness({ width, height, mmPerPixel, origin_mm, values }, plan.layout, offsets, speedAt, speed);
    expect(e.rampBins).toBeGreaterThan(6);
    expect(e.rampSpread).toBeLessThanOrEqual(0.1);
    await b.sim.stop();
  }, 120_000);
});

describe('cancelling or pausing a slow pass', () => {
  // A pass slower than a few mm/s once ran on for many seconds after Cancel or Pause
  // (at 2 mm/s Cancel took 54 s and the tool went on 30 mm): each 20 mm piece was
  // locked whole once sent. Pieces now last at most PASS_PIECE_S at the pass's speed.
  for (const [speed, action] of [
    [1, 'cancel'],
    [2, 'cancel'],
    [2, 'pause'],
    [20, 'cancel'],
  ] as const) {
    it(`at ${speed} mm/s, ${action} brings the tool to rest within half a second, where it was`, async () => {
      const b = await startMachine(lightPainter());
      const plan = planRaster(textBitmap('HI', 8), settings(speed), rasterMachine(b.maxl.config, [20, 100]));
      if (isProblem(plan)) throw new Error(plan.error);
      for (const m of plan.moves) await settle(b.scheduler, b.maxl.addSegmentToQueue(m), 1_000_000);
      const tool = () => {
        b.sim.sync();
        return b.sim.plant.toolXY();
      };
      // Run until the tool is 2 mm into the picture, then press Cancel (or Pause). The
      // travel from home to the start runs at the top speed (once at the painting speed:
      // 100 s at 1 mm/s), so a few seconds are enough.
      const deadline = b.scheduler.now() + 5_000_000 + 3_000_000 / speed;
      while (!(tool()[0] >= plan.layout.x0 + 2 && Math.abs(tool()[1] - 100) < 0.1)) {
        if (b.scheduler.now() > deadline) throw new Error('the pass never reached the picture');
        await b.scheduler.advance(10_000);
      }
      const pressedAt = tool()[0];
      const t0 = b.scheduler.now();
      await settle(b.scheduler, action === 'cancel' ? b.maxl.cancel() : b.maxl.pause(), 60_000_000);
      const took_s = (b.scheduler.now() - t0) / 1e6;
      await b.scheduler.advance(500_000);
      const restsAt = tool()[0];
      expect(took_s).toBeLessThan(0.5);
      // At speed v it runs on at most v · 0.5 s, plus the belt's give.
      expect(restsAt - pressedAt).toBeLessThan(speed * 0.5 + 0.2);
      await b.sim.stop();
    }, 120_000);
  }
});
