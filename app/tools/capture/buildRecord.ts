/**
 * Worker side: turns what the author captured over a test motion into a self-contained
 * CaptureRecord (protocol.ts): every sensor's samples in the window, the plan read at
 * each sample's author time, the planned acceleration curve, the as-planned segments,
 * the metadata, and the analysis of the accelerometer channel along the motion's axis.
 */
import type { Maxl } from '../../../core/index.ts';
import { analyseCapture } from '../../../core/capture/analysis.ts';
import type { SensorCapture } from '../../../core/capture/sensorCapture.ts';
import type { PlannedMotion, TestMotion } from '../../../core/capture/testMotions.ts';
import type { Bno055 } from '../../../core/sim/plant/bno055.ts';
import { resonancePeak_hz, stampTruth } from '../../../core/sim/plant/bno055Truth.ts';
import type { SpringParameters } from '../../../core/sim/plant/springResponse.ts';
import { lostBeforeIndex } from '../../../core/capture/sampleGaps.ts';
import { PLAN_STEP_US, type CaptureAnalysisView, type CaptureRecord, type PlannedSegment, type SensorTrace, type SimulatorTruth } from './protocol.ts';
import { decimateMax } from './decimate.ts';

export interface RecordInput {
  maxl: Maxl;
  id: string;
  date: string;
  motion: TestMotion;
  planned: PlannedMotion;
  machine: string;
  config: CaptureRecord['config'];
  start_us: number;
  end_us: number;
  /** each capture's size when the motion began, by "device/reader" */
  firstIndex: ReadonlyMap<string, number>;
  cutShort: string | null;
  warnings: string[];
  /** on a simulated machine: its accelerometer (recording its samples), the board reading it, and the belt spring */
  truth?: { chip: Bno055; device: string; spring: SpringParameters } | null;
}

/** Points of the spectrum kept for the plot. */
const SPECTRUM_POINTS = 1500;

export function buildRecord(input: RecordInput): CaptureRecord {
  const { maxl, start_us, end_us } = input;
  const axes = maxl.config.motionAxes;
  const horizon = maxl.history.horizon_us;
  const warnings = [...input.warnings];
  if (start_us < horizon) {
    warnings.push(`The as-planned history no longer holds the plan before ${(horizon / 1e6).toFixed(3)} s (it keeps ${maxl.history.capacity} segments): planned cells there are empty.`);
  }
  const band = sweptBand(input.motion, input.planned, input.cutShort ? (end_us - start_us) / 1e6 : null);
  if (band.cutAt_hz !== null && input.motion.kind === 'sweep') {
    const { fromHz, toHz } = input.motion;
    const reached = band.cutAt_hz.toFixed(1);
    warnings.push(
      `Cut short at about ${reached} Hz of the ${fromHz}–${toHz} Hz sweep: the spectrum's peak is looked for in ${fromHz}–${reached} Hz only, so a resonance above ${reached} Hz is not in this capture (run the whole sweep to find it).`,
    );
  }
  const sensors: SensorTrace[] = [];
  for (const [key, capture] of maxl.captures) sensors.push(traceOf(maxl, capture, input.firstIndex.get(key) ?? 0, end_us, horizon));

  const steps = Math.max(1, Math.floor((end_us - start_us) / PLAN_STEP_US) + 1);
  const plan = { t_us: new Float64Array(steps), acceleration: axes.map(() => new Float64Array(steps)) };
  for (let j = 0; j < steps; j++) {
    const t = start_us + j * PLAN_STEP_US;
    plan.t_us[j] = t;
    const s = t < horizon ? null : maxl.sample(t);
    axes.forEach((_, i) => (plan.acceleration[i][j] = s ? s.acceleration[i] : NaN));
  }

  const segments: PlannedSegment[] = [];
  const h = maxl.history;
  for (let i = Math.max(0, h.indexAt(start_us)); i < h.size; i++) {
    const r = h.at(i);
    if (r.startTime_us > end_us) break;
    segments.push({ startTime_us: r.startTime_us, duration_s: r.duration_s, length: r.length, timing: [...r.timing], start: [...r.start], unit: [...r.unit] });
  }

  return {
    id: input.id,
    date: input.date,
    description: input.planned.description,
    motion: input.motion,
    machine: input.machine,
    config: input.config,
    firmware: maxl.devices().map((d) => ({ device: d.name, link: d.label, firmware: d.firmware })),
    syncError_us: maxl.estimate().syncError_us,
    start_us,
    end_us,
    cutShort: input.cutShort,
    warnings,
    axes,
    plan,
    segments,
    sensors,
    analysis: analyse(maxl, sensors, input.motion, band.band_hz),
    simulatorTruth: truthOf(sensors, input.truth ?? null),
  };
}

function truthOf(sensors: SensorTrace[], truth: RecordInput['truth'] | null): SimulatorTruth | null {
  if (!truth || !truth.chip.record) return null;
  const trace = sensors.find((s) => s.device === truth.device && s.values.length === 3);
  if (!trace) return null;
  // Skipping the chip's records of samples lost on the link (by value alone, the sample after
  // a lost batch can match a lost one with the same values, a few reads early).
  const t = stampTruth(truth.chip, trace.author_us, trace.values, 0, trace.author_us.length, lostBeforeIndex(trace.gaps));
  return {
    device: truth.device,
    stampErrorWorst_us: t.worst_us,
    stampErrorMean_us: t.mean_us,
    matched: t.matched,
    unmatched: t.unmatched,
    chipSamples: t.chipSamples,
    naturalFrequency_hz: truth.spring.naturalFrequency_hz,
    damping: truth.spring.damping,
    truePeak_hz: resonancePeak_hz(truth.spring.naturalFrequency_hz, truth.spring.damping),
  };
}

function traceOf(maxl: Maxl, capture: SensorCapture, firstIndex: number, end_us: number, horizon: number): SensorTrace {
  const first = Math.min(firstIndex, capture.size);
  // Only the samples from the motion's start are copied (the capture holds every sample
  // since the machine started), and only up to the window's end.
  const after = capture.slice('time', first, capture.size);
  let n = after.length;
  while (n > 0 && after[n - 1] > end_us) n--;
  const last = first + n;
  const slice = (column: Parameters<SensorCapture['slice']>[0]) => capture.slice(column, first, last);
  const axes = maxl.config.motionAxes;
  const author_us = after.slice(0, n);
  const planned = {
    position: axes.map(() => new Float64Array(n)),
    velocity: axes.map(() => new Float64Array(n)),
    acceleration: axes.map(() => new Float64Array(n)),
    speed: new Float64Array(n),
    pathAcceleration: new Float64Array(n),
  };
  for (let k = 0; k < n; k++) {
    const s = author_us[k] < horizon ? null : maxl.sample(author_us[k]);
    axes.forEach((_, i) => {
      planned.position[i][k] = s ? s.position[i] : NaN;
      planned.velocity[i][k] = s ? s.velocity[i] : NaN;
      planned.acceleration[i][k] = s ? s.acceleration[i] : NaN;
    });
    planned.speed[k] = s ? s.speed : NaN;
    planned.pathAcceleration[k] = s ? s.pathAcceleration : NaN;
  }
  // The capture is keyed by the session's label (a port name, or "sim:…"); the record keeps the device's own name.
  const device = maxl.devices().find((d) => d.label === capture.device)?.name ?? capture.device;
  return {
    device,
    reader: capture.reader,
    channelNames: channelNames(capture),
    author_us,
    device_us: slice('deviceTime'),
    batch: slice('batch'),
    index: slice('index'),
    seq: slice('sequence'),
    values: Array.from({ length: capture.channels }, (_, c) => slice(c)),
    // Gaps with received samples on both sides inside the window, re-indexed to it.
    gaps: capture.gaps.filter((g) => g.index > first && g.index < last).map((g) => ({ ...g, index: g.index - first })),
    planned,
  };
}

/** x, y, z for a three-channel sensor (an accelerometer), else the reader's name and index. */
function channelNames(capture: SensorCapture): string[] {
  if (capture.channels === 3) return ['ax_mm_s2', 'ay_mm_s2', 'az_mm_s2'].map((n) => `${capture.reader}_${n}`);
  return Array.from({ length: capture.channels }, (_, c) => `${capture.reader}${c}`);
}

/**
 * The band the motion excited: the planned one, or for a sweep cut short after
 * `cutAfter_s` (null: it ran whole) only the frequencies it reached. The sweep's
 * frequency rises by `hzPerSecond` each second (each stroke of period 1/f raises f by
 * rate/f, so df/dt = rate): f(t) = from + rate·t. The time from the run's start to its
 * end overstates t by the start lead and the braking (milliseconds), so the band is a
 * hair wide, never narrow.
 */
export function sweptBand(motion: TestMotion, planned: PlannedMotion, cutAfter_s: number | null): { band_hz: [number, number]; cutAt_hz: number | null } {
  if (motion.kind !== 'sweep' || cutAfter_s === null) return { band_hz: planned.band_hz, cutAt_hz: null };
  const reached = motion.fromHz + motion.hzPerSecond * Math.max(0, cutAfter_s);
  if (reached >= planned.band_hz[1]) return { band_hz: planned.band_hz, cutAt_hz: null };
  return { band_hz: [planned.band_hz[0], reached], cutAt_hz: reached };
}

function analyse(maxl: Maxl, sensors: SensorTrace[], motion: TestMotion, band_hz: [number, number]): CaptureAnalysisView | null {
  const sensor = sensors.findIndex((s) => s.values.length >= 1 && s.author_us.length >= 16);
  if (sensor < 0) return null;
  const trace = sensors[sensor];
  const axis = maxl.config.motionAxes.indexOf(motion.axis);
  const channel = axis < trace.values.length ? axis : 0;
  let result;
  try {
    result = analyseCapture({
      times_us: trace.author_us,
      measured: trace.values[channel],
      gapsBefore: trace.gaps.filter((g) => g.kind === 'lost').map((g) => g.index),
      planned: (t) => maxl.sample(t).acceleration[axis],
      fMin_hz: band_hz[0],
      fMax_hz: band_hz[1],
    });
  } catch {
    return null;
  }
  const nyquist = result.sampleRate_hz / 2;
  const top = Math.min(nyquist, Number.isFinite(band_hz[1]) ? band_hz[1] * 1.3 : nyquist);
  const bins = Math.min(result.spectrum.amplitude.length, Math.floor(top / result.spectrum.binHz) + 1);
  const { x, y } = decimateMax(result.spectrum.amplitude.subarray(0, bins), result.spectrum.binHz, SPECTRUM_POINTS);
  return {
    sensor,
    axis: motion.axis,
    channel,
    lag_ms: (result.lag?.lag_s ?? NaN) * 1000,
    correlation: result.lag?.correlation ?? NaN,
    rms_mm_s2: result.rmsError,
    peak_hz: result.peak?.frequency_hz ?? NaN,
    peakAmplitude: result.peak?.amplitude ?? NaN,
    band_hz: [band_hz[0], Math.min(band_hz[1], nyquist)],
    sampleRate_hz: result.sampleRate_hz,
    spectrumHz: x,
    spectrumAmplitude: y,
  };
}
