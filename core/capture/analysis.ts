/**
 * What a capture tells about the machine: measured against planned acceleration on one
 * axis (the lag by cross-correlation, the RMS error), and the spectrum of the measured
 * acceleration with its peak.
 *
 * The samples come stamped in author time, nearly but not exactly evenly (the device's
 * crystal runs a few ppm off the author's clock, and the clock model is refitted now and
 * then). The estimators want a uniform grid, so the measured values are interpolated
 * linearly onto t_j = t₀ + j·P, P the median sample interval; a grid point that falls in
 * a gap (lost samples between its neighbours) is marked invalid and never bridged. The
 * spectrum fills invalid points with the mean (zero after the mean is removed), the lag
 * and RMS leave them out.
 */
import { crossCorrelationLag, rmsDifference, type LagEstimate } from './lag.ts';
import { amplitudeSpectrum, smoothSpectrum, spectrumPeak, type Spectrum, type SpectrumPeak } from './spectrum.ts';

export interface AnalysisInput {
  /** author µs of each sample, ascending */
  times_us: ArrayLike<number>;
  /** the measured acceleration, mm/s², one per sample */
  measured: ArrayLike<number>;
  /** indices i where samples were lost between sample i − 1 and i */
  gapsBefore?: Iterable<number>;
  /** the planned acceleration on the same axis, mm/s², at an author time */
  planned(t_us: number): number;
  /** where to look for the spectrum's peak (default 5 Hz … Nyquist) */
  fMin_hz?: number;
  fMax_hz?: number;
  /** the cross-correlation's search range (default ±100 ms) */
  maxLag_s?: number;
  /** the spectrum's smoothing, ± Hz (default 0.3; spectrum.ts) */
  smoothing_hz?: number;
}

export interface CaptureAnalysis {
  samples: number;
  /** the median interval between samples, s, and the grid's rate */
  samplePeriod_s: number;
  sampleRate_hz: number;
  lag: LagEstimate | null;
  /** √(mean (measured − planned)²) at the grid points, mm/s² (no shift applied) */
  rmsError: number;
  /** the measured acceleration's amplitude spectrum, smoothed (spectrum.ts) */
  spectrum: Spectrum;
  /** its largest peak in the band, refined */
  peak: SpectrumPeak | null;
}

/** The median of the positive differences of an ascending series, leaving out those across a gap. */
export function medianInterval(times: ArrayLike<number>, gapsBefore: ReadonlySet<number> = new Set()): number {
  const d: number[] = [];
  for (let i = 1; i < times.length; i++) if (!gapsBefore.has(i) && times[i] > times[i - 1]) d.push(times[i] - times[i - 1]);
  if (d.length === 0) return NaN;
  d.sort((a, b) => a - b);
  return d[d.length >> 1];
}

/** The measured values on the uniform grid, with validity, and the planned values at the grid points. */
export function resampleOnGrid(input: AnalysisInput): { grid_us: Float64Array; measured: Float64Array; planned: Float64Array; valid: Uint8Array; period_us: number } {
  const { times_us: t, measured: m } = input;
  const gaps = new Set(input.gapsBefore ?? []);
  const period_us = medianInterval(t, gaps);
  if (!(period_us > 0) || t.length < 4) throw new RangeError(`capture analysis: need at least 4 samples at distinct times, got ${t.length}`);
  const count = Math.floor((t[t.length - 1] - t[0]) / period_us) + 1;
  const grid_us = new Float64Array(count);
  const measured = new Float64Array(count);
  const planned = new Float64Array(count);
  const valid = new Uint8Array(count);
  let i = 0;
  for (let j = 0; j < count; j++) {
    const tj = t[0] + j * period_us;
    grid_us[j] = tj;
    planned[j] = input.planned(tj);
    while (i + 2 < t.length && t[i + 1] <= tj) i++;
    // tj in [t[i], t[i+1]] (or at the very end)
    if (tj <= t[i]) {
      measured[j] = m[i];
      valid[j] = 1;
    } else if (i + 1 < t.length && !gaps.has(i + 1) && tj <= t[i + 1]) {
      const f = (tj - t[i]) / (t[i + 1] - t[i]);
      measured[j] = m[i] + f * (m[i + 1] - m[i]);
      valid[j] = 1;
    }
  }
  return { grid_us, measured, planned, valid, period_us };
}

export function analyseCapture(input: AnalysisInput): CaptureAnalysis {
  const g = resampleOnGrid(input);
  const period_s = g.period_us * 1e-6;
  const rate = 1 / period_s;
  const validMask = Array.from(g.valid, (v) => v === 1);
  let mean = 0;
  let n = 0;
  for (let j = 0; j < g.measured.length; j++) if (validMask[j]) ((mean += g.measured[j]), n++);
  mean /= n;
  const filled = g.measured.map((v, j) => (validMask[j] ? v : mean));
  const spectrum = smoothSpectrum(amplitudeSpectrum(filled, rate), input.smoothing_hz ?? 0.3);
  return {
    samples: input.times_us.length,
    samplePeriod_s: period_s,
    sampleRate_hz: rate,
    lag: crossCorrelationLag(g.planned, g.measured, period_s, input.maxLag_s ?? 0.1, validMask),
    rmsError: rmsDifference(g.measured, g.planned, validMask),
    spectrum,
    peak: spectrumPeak(spectrum, input.fMin_hz ?? 5, input.fMax_hz ?? rate / 2),
  };
}
