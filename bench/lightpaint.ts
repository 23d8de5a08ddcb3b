/**
 * `npm run bench -- lightpaint`: the light-painting tool's job on the simulated
 * light painter (real LightPainter and Stepper firmware in wasm, the CoreXY
 * plant with its springy tool), in virtual time. For each speed (100 and
 * 200 mm/s, the preset's top), the worst over a word painted left to right and
 * right to left, on 3 simulator seeds, of:
 *
 *   placementErrorMm     max over every run of lit columns on every LED of
 *                        |exposure centroid − the run's centre in the bitmap|
 *                        (a lone column is a run of one), ramps included
 *                        (exposureAnalysis.ts); target ≤ pixelPitchMm / 4
 *   edgeErrorMm          max |half-plateau crossing − the bitmap's edge| (stricter)
 *   columnMismatches     columns lit that should be dark or dark that should be lit
 *   pixelPitchMm         the pitch along the move (2 mm, the default)
 *   exposurePixelsPerPitch  the exposure image's resolution (target ≥ 4)
 *   exposurePerMmSpread  on an all-lit bar, max |exposure per mm / mean at cruise − 1|
 *                        over the 1 mm bins of the ramps where the planned speed is
 *                        ≥ 20 % of cruise (brightest channel); target ≤ 0.10
 *   cruiseSpread         the same over the cruise bins
 *   rampBins             how many ramp bins that spread covers
 *   columnsOnRamps       columns of the word drawn below 99 % of cruise
 */
import { lightPainter } from '../core/sim/presets/index.ts';
import { startMachine } from '../core/system/harness.ts';
import { emptyBitmap, textBitmap } from '../app/tools/lightpaint/bitmap.ts';
import { analyseColumns, exposureEvenness } from '../app/tools/lightpaint/exposureAnalysis.ts';
import { ledColour } from '../app/tools/lightpaint/ledColour.ts';
import { DEFAULT_EVALUATION_PRECISION_MS, type RasterSettings } from '../app/tools/lightpaint/raster.ts';
import { paintOnSim } from '../app/tools/lightpaint/simPainting.ts';

const WORD = 'HELLO';
const PITCH = 2;
const SEEDS = [1, 2, 3];
const ORIGIN = [30, 100];

async function atSpeed(speed: number) {
  const worst = { placementErrorMm: 0, edgeErrorMm: 0, columnMismatches: 0, exposurePerMmSpread: 0, cruiseSpread: 0, rampBins: Infinity, columnsOnRamps: Infinity };
  let pxPerPitch = 0;
  for (const seed of SEEDS) {
    for (const reverse of [false, true]) {
      const settings: RasterSettings = { speed, pitch_mm: PITCH, colour: ledColour([255, 160, 64], 1, 2.2), reverse, evaluationPrecision_ms: DEFAULT_EVALUATION_PRECISION_MS };
      const b = await startMachine(lightPainter(), { seed });
      const word = await paintOnSim(b, textBitmap(WORD, 8), settings, ORIGIN);
      const a = analyseColumns(word.exposure, word.layout, word.ledOffsets_mm);
      worst.placementErrorMm = Math.max(worst.placementErrorMm, a.placementError_mm);
      worst.edgeErrorMm = Math.max(worst.edgeErrorMm, a.edgeError_mm);
      worst.columnMismatches = Math.max(worst.columnMismatches, a.mismatches.length);
      const ramped = word.layout.bits.filter((_, c) => word.speedAt(word.layout.x0 + (c + 0.5) * PITCH) < 0.99 * speed).length;
      worst.columnsOnRamps = Math.min(worst.columnsOnRamps, ramped);
      pxPerPitch = PITCH / word.exposure.mmPerPixel;
      const bar = emptyBitmap(60, 8);
      bar.lit.fill(1);
      const lit = await paintOnSim(b, bar, settings, ORIGIN);
      const e = exposureEvenness(lit.exposure, lit.layout, lit.ledOffsets_mm, lit.speedAt, lit.plan.speed);
      worst.exposurePerMmSpread = Math.max(worst.exposurePerMmSpread, e.rampSpread);
      worst.cruiseSpread = Math.max(worst.cruiseSpread, e.cruiseSpread);
      worst.rampBins = Math.min(worst.rampBins, e.rampBins);
      await b.sim.stop();
    }
  }
  const r = (v: number) => Math.round(v * 10000) / 10000;
  return {
    speedMmPerS: speed,
    placementErrorMm: r(worst.placementErrorMm),
    edgeErrorMm: r(worst.edgeErrorMm),
    pixelPitchMm: PITCH,
    placementTargetMm: PITCH / 4,
    exposurePixelsPerPitch: pxPerPitch,
    columnMismatches: worst.columnMismatches,
    columnsOnRamps: worst.columnsOnRamps,
    exposurePerMmSpread: r(worst.exposurePerMmSpread),
    cruiseSpread: r(worst.cruiseSpread),
    rampBins: worst.rampBins,
  };
}

const results = [];
for (const speed of [100, 200]) {
  const one = await atSpeed(speed);
  console.log(`${speed} mm/s: placement ${one.placementErrorMm} mm (edges ${one.edgeErrorMm} mm), ramp light per mm ±${(one.exposurePerMmSpread * 100).toFixed(1)} %`);
  results.push(one);
}
console.log(JSON.stringify({ word: WORD, seeds: SEEDS.length, directions: 2, evaluationPrecisionMs: DEFAULT_EVALUATION_PRECISION_MS, speeds: results }));
