/**
 * The capture tool's commands (page → worker) and events (worker → page), and the
 * record a finished capture becomes: self-contained (samples, the plan at each sample,
 * the plan's segments, metadata and analysis), so that it can be kept in IndexedDB,
 * exported and compared long after its author is gone.
 */
import type { MaxlConfig } from '../../../core/index.ts';
import type { SampleGap } from '../../../core/capture/sampleGaps.ts';
import type { TestMotion } from '../../../core/capture/testMotions.ts';

export type { TestMotion } from '../../../core/capture/testMotions.ts';

export type CaptureCommand =
  | { tool: 'capture'; type: 'capture-run'; motion: TestMotion }
  | { tool: 'capture'; type: 'capture-cancel' };

export interface CaptureProgress {
  state: 'running' | 'settling';
  description: string;
  elapsed_s: number;
  /** the motion's own length, s */
  duration_s: number;
  /** samples received so far, over every sensor */
  samples: number;
  /** samples reported lost so far */
  lost: number;
}

export type CaptureEvent =
  | { tool: 'capture'; type: 'capture-progress'; progress: CaptureProgress }
  /**
   * The record, kept in IndexedDB by the worker before it is sent (a 10-minute capture is
   * tens of MB: cloning it into the store would hold the page); `notKept` says why it
   * could not be kept, null when it was.
   */
  | { tool: 'capture'; type: 'capture-done'; record: CaptureRecord; notKept: string | null }
  | { tool: 'capture'; type: 'capture-failed'; message: string };

/** One sensor reader's samples over the capture, with the plan at each sample. */
export interface SensorTrace {
  device: string;
  reader: string;
  channelNames: string[];
  /** per sample: author µs, the device's u32 stamp, batch (unwrapped), index in batch, sample number */
  author_us: Float64Array;
  device_us: Float64Array;
  batch: Float64Array;
  index: Float64Array;
  seq: Float64Array;
  /** per channel, per sample */
  values: Float64Array[];
  /** gaps (lost or duplicate batches) with `index` relative to this trace */
  gaps: SampleGap[];
  /** the plan at each sample (NaN where it is not known: before the history's horizon) */
  planned: {
    position: Float64Array[];
    velocity: Float64Array[];
    acceleration: Float64Array[];
    speed: Float64Array;
    pathAcceleration: Float64Array;
  };
}

/** One as-planned segment, as the history keeps it (core/trajectory/history.ts). */
export interface PlannedSegment {
  startTime_us: number;
  duration_s: number;
  length: number;
  timing: number[];
  start: number[];
  unit: number[];
}

export interface CaptureAnalysisView {
  sensor: number;
  axis: string;
  channel: number;
  lag_ms: number;
  correlation: number;
  rms_mm_s2: number;
  peak_hz: number;
  peakAmplitude: number;
  band_hz: [number, number];
  sampleRate_hz: number;
  /** the smoothed amplitude spectrum, decimated for plotting */
  spectrumHz: Float64Array;
  spectrumAmplitude: Float64Array;
}

export interface CaptureRecord {
  id: string;
  /** ISO date of the capture */
  date: string;
  description: string;
  motion: TestMotion;
  /** preset id, or "boards" */
  machine: string;
  config: Omit<MaxlConfig, 'transforms'>;
  firmware: Array<{ device: string; link: string; firmware: string }>;
  /** the worst clock-sync error over the devices at the end, µs */
  syncError_us: number;
  start_us: number;
  end_us: number;
  /** cancelled or stopped before the motion's end */
  cutShort: string | null;
  warnings: string[];
  axes: string[];
  /** the planned acceleration every PLAN_STEP_US over [start, end], per axis */
  plan: { t_us: Float64Array; acceleration: Float64Array[] };
  segments: PlannedSegment[];
  sensors: SensorTrace[];
  analysis: CaptureAnalysisView | null;
  /** On a simulated machine with an accelerometer: the simulator's ground truth (core/sim/plant/bno055Truth.ts). */
  simulatorTruth: SimulatorTruth | null;
}

export interface SimulatorTruth {
  device: string;
  /** worst and mean |stamp − centre of the chip's averaging window|, µs, over the samples matched */
  stampErrorWorst_us: number;
  stampErrorMean_us: number;
  matched: number;
  unmatched: number;
  /** samples the board read from the chip over the capture */
  chipSamples: number;
  /** the plant's belt spring, and the peak of its response f₀·√(1 − 2ζ²) */
  naturalFrequency_hz: number;
  damping: number;
  truePeak_hz: number;
}

/** The planned curve's resolution in a record, µs. */
export const PLAN_STEP_US = 1000;

/** The typed arrays of a record, to transfer with postMessage. */
export function recordTransferables(r: CaptureRecord): Transferable[] {
  const out: ArrayBufferLike[] = [r.plan.t_us.buffer, ...r.plan.acceleration.map((a) => a.buffer)];
  for (const s of r.sensors) {
    out.push(s.author_us.buffer, s.device_us.buffer, s.batch.buffer, s.index.buffer, s.seq.buffer, ...s.values.map((v) => v.buffer));
    const p = s.planned;
    out.push(...p.position.map((a) => a.buffer), ...p.velocity.map((a) => a.buffer), ...p.acceleration.map((a) => a.buffer), p.speed.buffer, p.pathAcceleration.buffer);
  }
  if (r.analysis) out.push(r.analysis.spectrumHz.buffer, r.analysis.spectrumAmplitude.buffer);
  return [...new Set(out)] as Transferable[];
}
