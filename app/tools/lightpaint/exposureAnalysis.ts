/**
 * Reads a long exposure back against the bitmap that made it: which columns
 * came out lit, where each lit run of columns landed, and how even the light
 * per mm is. The core tests, the bench and the e2e test (on the saved PNG) all
 * measure with this.
 *
 * The image is one channel (the colour's brightest), machine-oriented: pixel
 * (i, j) lies at origin + (i, j)·mmPerPixel, j growing with y. Each LED draws a
 * line at y = tool y + its offset; its profile along x sums the pixel rows
 * within half an LED spacing of that line (all of its light: the simulator
 * splats each deposit over the two nearest rows).
 *
 * Definitions (x in machine mm):
 *  - Lit: a column's mean exposure over its central half, [centre − p/4,
 *    centre + p/4], is above half the lit level (the median of that mean over
 *    the columns meant to be lit).
 *  - Placement error of a run of lit columns c0..c1 on one LED (neighbouring
 *    lit columns merge into one streak of light, so a run is what can be
 *    measured): its exposure centroid over [x0 + c0·p − p/2, x0 + (c1+1)·p + p/2]
 *    minus where the bitmap puts its centre, x0 + (c0 + c1 + 1)·p/2. A lone
 *    column is a run of one: its centroid against its centre.
 *  - Edge error: where the run's exposure crosses half its plateau, against
 *    x0 + c0·p and x0 + (c1+1)·p (linear between pixel centres).
 *  - Exposure per mm: an all-lit bar's exposure (every LED) in 1 mm bins of x,
 *    against the mean of the bins at cruise (planned speed ≥ 99 % of cruise).
 */
import type { RasterLayout } from './raster.ts';

export interface ExposureChannel {
  width: number;
  height: number;
  mmPerPixel: number;
  /** mm, the machine position of pixel (0, 0)'s centre. */
  origin_mm: readonly [number, number];
  /** width × height values, row j (y) by row; j grows with y. */
  values: ArrayLike<number>;
}

export interface RunPlacement {
  led: number;
  firstColumn: number;
  lastColumn: number;
  /** mm, measured centroid minus the bitmap's centre of the run. */
  centroidError_mm: number;
  /** mm, measured minus planned, at either edge. */
  leftEdgeError_mm: number;
  rightEdgeError_mm: number;
}

export interface ColumnMismatch {
  column: number;
  led: number;
  expected: boolean;
  /** The column's central mean over the lit level. */
  level: number;
}

export interface ColumnAnalysis {
  litLevel: number;
  mismatches: ColumnMismatch[];
  runs: RunPlacement[];
  /** mm, the largest |centroid error| of any run. */
  placementError_mm: number;
  /** mm, the largest |edge error|. */
  edgeError_mm: number;
  /** Darkest lit column and brightest dark one, as fractions of the lit level. */
  minLit: number;
  maxDark: number;
}

/** Each LED's exposure along x: profiles[led][i] for pixel column i. */
export function ledProfiles(img: ExposureChannel, toolY: number, ledOffsets_mm: readonly number[]): Float64Array[] {
  const spacing = ledOffsets_mm.length > 1 ? Math.abs(ledOffsets_mm[1] - ledOffsets_mm[0]) : 4 * img.mmPerPixel;
  return ledOffsets_mm.map((offset) => {
    const y = toolY + offset;
    const profile = new Float64Array(img.width);
    for (let j = 0; j < img.height; j++) {
      const yj = img.origin_mm[1] + j * img.mmPerPixel;
      if (Math.abs(yj - y) >= spacing / 2) continue;
      for (let i = 0; i < img.width; i++) profile[i] += img.values[j * img.width + i];
    }
    return profile;
  });
}

function xOf(img: ExposureChannel, i: number): number {
  return img.origin_mm[0] + i * img.mmPerPixel;
}

function meanOver(img: ExposureChannel, profile: Float64Array, a: number, b: number): number {
  let sum = 0;
  let n = 0;
  for (let i = 0; i < img.width; i++) {
    const x = xOf(img, i);
    if (x >= a && x <= b) {
      sum += profile[i];
      n++;
    }
  }
  return n > 0 ? sum / n : 0;
}

function median(values: number[]): number {
  const s = [...values].sort((a, b) => a - b);
  return s.length === 0 ? 0 : s[Math.floor(s.length / 2)];
}

/** x where the profile first reaches `level` scanning from a towards b (a > b scans leftwards); NaN if never. */
function crossing(img: ExposureChannel, profile: Float64Array, a: number, b: number, level: number): number {
  const step = a < b ? 1 : -1;
  const i0 = Math.max(0, Math.min(img.width - 1, Math.round((a - img.origin_mm[0]) / img.mmPerPixel)));
  const i1 = Math.max(0, Math.min(img.width - 1, Math.round((b - img.origin_mm[0]) / img.mmPerPixel)));
  for (let i = i0; i !== i1; i += step) {
    const next = i + step;
    if (profile[i] < level && profile[next] >= level) {
      const f = (level - profile[i]) / (profile[next] - profile[i]);
      return xOf(img, i) + step * f * img.mmPerPixel;
    }
  }
  return NaN;
}

export function analyseColumns(img: ExposureChannel, layout: RasterLayout, ledOffsets_mm: readonly number[]): ColumnAnalysis {
  const { x0, pitch_mm: p, bits } = layout;
  const profiles = ledProfiles(img, layout.y, ledOffsets_mm);
  const central = profiles.map((profile) => bits.map((_, c) => meanOver(img, profile, x0 + (c + 0.25) * p, x0 + (c + 0.75) * p)));
  const litMeans: number[] = [];
  bits.forEach((b, c) => profiles.forEach((_, led) => (b >> led) & 1 && litMeans.push(central[led][c])));
  const litLevel = median(litMeans);
  const mismatches: ColumnMismatch[] = [];
  let minLit = Infinity;
  let maxDark = 0;
  bits.forEach((b, c) =>
    profiles.forEach((_, led) => {
      const expected = ((b >> led) & 1) === 1;
      const level = litLevel > 0 ? central[led][c] / litLevel : 0;
      if (expected) minLit = Math.min(minLit, level);
      else maxDark = Math.max(maxDark, level);
      if (expected !== level > 0.5) mismatches.push({ column: c, led, expected, level });
    }),
  );
  const runs: RunPlacement[] = [];
  profiles.forEach((profile, led) => {
    for (let c = 0; c < bits.length; c++) {
      if (!((bits[c] >> led) & 1)) continue;
      let last = c;
      while (last + 1 < bits.length && (bits[last + 1] >> led) & 1) last++;
      const left = x0 + c * p;
      const right = x0 + (last + 1) * p;
      let sum = 0;
      let moment = 0;
      for (let i = 0; i < img.width; i++) {
        const x = xOf(img, i);
        if (x < left - p / 2 || x > right + p / 2) continue;
        sum += profile[i];
        moment += profile[i] * x;
      }
      const inset = Math.min(p / 4, 1);
      const plateau = meanOver(img, profile, left + inset, right - inset);
      runs.push({
        led,
        firstColumn: c,
        lastColumn: last,
        centroidError_mm: sum > 0 ? moment / sum - (left + right) / 2 : NaN,
        leftEdgeError_mm: crossing(img, profile, left - p / 2, right, plateau / 2) - left,
        rightEdgeError_mm: crossing(img, profile, right + p / 2, left, plateau / 2) - right,
      });
      c = last;
    }
  });
  const worst = (f: (r: RunPlacement) => number) => runs.reduce((m, r) => Math.max(m, Number.isNaN(f(r)) ? Infinity : Math.abs(f(r))), 0);
  return {
    litLevel,
    mismatches,
    runs,
    placementError_mm: worst((r) => r.centroidError_mm),
    edgeError_mm: Math.max(
      worst((r) => r.leftEdgeError_mm),
      worst((r) => r.rightEdgeError_mm),
    ),
    minLit: minLit === Infinity ? 0 : minLit,
    maxDark,
  };
}

export interface EvennessBin {
  /** mm, the bin's centre. */
  x: number;
  /** mm/s planned at x. */
  speed: number;
  /** Exposure in the bin per mm, over the cruise mean. */
  relative: number;
}

export interface Evenness {
  /** Exposure per mm at cruise (all LEDs, value·s/mm). */
  cruisePerMm: number;
  /** Worst |relative − 1| over the ramp bins at ≥ 20 % of cruise. */
  rampSpread: number;
  /** Worst |relative − 1| over the cruise bins. */
  cruiseSpread: number;
  rampBins: number;
  cruiseBins: number;
  bins: EvennessBin[];
}

/**
 * Light per mm along an all-lit bar painted over [x0, x0 + n·p]: 1 mm bins
 * (two pixels at 0.5 mm/px) from half a mm inside either end, every LED
 * summed. `speedAt(x)` is the planned speed where the tool was at x.
 */
export function exposureEvenness(
  img: ExposureChannel,
  layout: RasterLayout,
  ledOffsets_mm: readonly number[],
  speedAt: (x: number) => number,
  cruise: number,
  bin_mm = 1,
): Evenness {
  const profiles = ledProfiles(img, layout.y, ledOffsets_mm);
  const total = new Float64Array(img.width);
  for (const p of profiles) for (let i = 0; i < img.width; i++) total[i] += p[i];
  const start = layout.x0 + 0.5;
  const end = layout.x0 + layout.bits.length * layout.pitch_mm - 0.5;
  const raw: Array<{ x: number; speed: number; perMm: number }> = [];
  for (let a = start; a + bin_mm <= end + 1e-9; a += bin_mm) {
    let sum = 0;
    for (let i = 0; i < img.width; i++) {
      const x = xOf(img, i);
      // Half-open [a, a + bin): every pixel centre falls in one bin.
      if (x >= a - 1e-9 && x < a + bin_mm - 1e-9) sum += total[i];
    }
    raw.push({ x: a + bin_mm / 2, speed: speedAt(a + bin_mm / 2), perMm: sum / bin_mm });
  }
  const cruiseBins = raw.filter((b) => b.speed >= 0.99 * cruise);
  const cruisePerMm = cruiseBins.reduce((s, b) => s + b.perMm, 0) / Math.max(1, cruiseBins.length);
  const bins = raw.map((b) => ({ x: b.x, speed: b.speed, relative: cruisePerMm > 0 ? b.perMm / cruisePerMm : NaN }));
  const ramp = bins.filter((b) => b.speed >= 0.2 * cruise && b.speed < 0.99 * cruise);
  const cruising = bins.filter((b) => b.speed >= 0.99 * cruise);
  const spread = (list: EvennessBin[]) => list.reduce((m, b) => Math.max(m, Math.abs(b.relative - 1)), 0);
  return { cruisePerMm, rampSpread: spread(ramp), cruiseSpread: spread(cruising), rampBins: ramp.length, cruiseBins: cruising.length, bins };
}
