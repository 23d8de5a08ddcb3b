/**
 * The light-painting job on the simulated light painter (real LightPainter and
 * Stepper firmware in wasm, CoreXY plant with its springy tool), in virtual
 * time: every column lands within a quarter pitch at 100 and 200 mm/s, ramps
 * included, and an all-lit bar gets even light per mm through the ramps.
 */
import { describe, expect, it } from 'vitest';
import { lightPainter } from '../../../core/sim/presets/index.ts';
import { startMachine } from '../../../core/system/harness.ts';
import { emptyBitmap, textBitmap } from './bitmap.ts';
import { analyseColumns, exposureEvenness } from './exposureAnalysis.ts';
import { ledColour } from './ledColour.ts';
import { DEFAULT_EVALUATION_PRECISION_MS, type RasterSettings } from './raster.ts';
import { paintOnSim } from './simPainting.ts';

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
