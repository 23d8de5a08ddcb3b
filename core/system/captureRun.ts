/**
 * A capture on the simulated accelerometer rig, in virtual time, judged against the
 * simulator's ground truth. Used by the capture system test and `npm run bench -- capture`.
 *
 * Ground truth of a sample's instant: the centre of the BNO055 model's averaging window
 * for the chip sample it is (core/sim/plant/bno055Truth.ts).
 *
 * The plant's resonance: the tool hangs on the belt as x'' = ω²(u − x) − 2ζω x'
 * (springResponse.ts), so from the carriage's acceleration ü (what the plan commands) to
 * the tool's acceleration ẍ (what the accelerometer feels)
 *
 *   H(s) = ω² / (s² + 2ζω s + ω²),   |H(jΩ)|² = ω⁴ / ((ω² − Ω²)² + (2ζωΩ)²)
 *
 * whose peak, d|H|²/dΩ = 0, is at Ω_r = ω·√(1 − 2ζ²): 27.899 Hz for 28 Hz and ζ = 0.06.
 * That is the peak of the response the spectrum shows (the undamped 28 Hz and the free
 * ringing's ω√(1 − ζ²) = 27.95 Hz are both within 0.4 % of it).
 */
import { accelRig } from '../sim/presets/index.ts';
import { analyseCapture, type CaptureAnalysis } from '../capture/analysis.ts';
import { limitsAlong, planTestMotion, type TestMotion } from '../capture/testMotions.ts';
import type { SampleGap, SensorCapture } from '../capture/sensorCapture.ts';
import { lostBeforeIndex } from '../capture/sampleGaps.ts';
import type { SimulatedMachineOptions } from '../sim/machine.ts';
import type { SpringParameters } from '../sim/plant/springResponse.ts';

function isSpring(s: SpringParameters | Record<string, SpringParameters>): s is SpringParameters {
  return typeof (s as SpringParameters).naturalFrequency_hz === 'number';
}
import { runJob, startMachine, type Bench } from './harness.ts';
import { resonancePeak_hz, stampTruth, type StampTruth } from '../sim/plant/bno055Truth.ts';

export { resonancePeak_hz } from '../sim/plant/bno055Truth.ts';

export type StampCheck = StampTruth;

/** Compares every captured sample from index `from` up to `to` (exclusive) with the chip's own record, skipping the records of samples lost on the link. */
export function checkStamps(b: Bench, capture: SensorCapture, from = 0, to = capture.size): StampCheck {
  const chip = b.sim.plant.accelerometer;
  if (!chip) throw new Error('the machine has no accelerometer');
  return stampTruth(chip, capture.timeColumn(), [0, 1, 2].map((c) => capture.channel(c)), from, to, lostBeforeIndex(capture.gaps));
}

export interface CaptureRunResult {
  bench: Bench;
  capture: SensorCapture;
  /** index of the first sample of the motion, and the motion's author-time span */
  firstSample: number;
  start_us: number;
  end_us: number;
  analysis: CaptureAnalysis;
  stamps: StampCheck;
  truePeak_hz: number;
  excitation_s: number;
  /**
   * Samples the board took over the motion (ground truth: the chip's samples read, from
   * the first received to the last), those received, and those the capture reported lost.
   */
  samplesExpected: number;
  samplesReceived: number;
  samplesLostReported: number;
}

/**
 * Runs `motion` on the accelerometer rig from x = 150 mm and analyses the capture over
 * the motion (plus 0.3 s of ringing after it).
 */
export async function runCaptureOnAccelRig(
  motion: TestMotion,
  seed = 1,
  sim: Partial<SimulatedMachineOptions> = {},
  onGap?: (gap: SampleGap) => void,
): Promise<CaptureRunResult> {
  const preset = accelRig();
  const b = await startMachine(preset, { seed, sim });
  if (onGap) b.maxl.on((e) => e.type === 'sampleGap' && onGap(e.gap));
  await runJob(b, [{ endPosition: [150] }]);
  const config = b.maxl.config;
  const planned = planTestMotion(motion, limitsAlong(config, motion.axis), b.maxl.nextMoveStart);
  const capture = b.maxl.captures.get('accelerometer/accel');
  if (!capture) throw new Error('no capture of accelerometer/accel');
  const firstSample = capture.size;
  const start_us = b.scheduler.now();
  await runJob(b, planned.moves, undefined, 5000, 700_000_000);
  const end_us = b.scheduler.now() + 300_000;
  await b.scheduler.advance(400_000);
  b.sim.sync();
  const times = capture.timeColumn();
  let last = times.length;
  while (last > firstSample && times[last - 1] > end_us) last--;
  const axis = 0;
  const gapsBefore = capture.gaps.filter((g) => g.kind === 'lost' && g.index > firstSample && g.index < last).map((g) => g.index - firstSample);
  const analysis = analyseCapture({
    times_us: times.subarray(firstSample, last),
    measured: capture.channel(axis).subarray(firstSample, last),
    gapsBefore,
    planned: (t) => b.maxl.sample(t).acceleration[axis],
    fMin_hz: planned.band_hz[0],
    fMax_hz: Math.min(planned.band_hz[1], 50),
  });
  const spring = preset.plant.spring;
  const p: SpringParameters = isSpring(spring) ? spring : spring[motion.axis];
  const stamps = checkStamps(b, capture, firstSample, last);
  return {
    bench: b,
    capture,
    firstSample,
    start_us,
    end_us,
    analysis,
    stamps,
    truePeak_hz: resonancePeak_hz(p.naturalFrequency_hz, p.damping),
    excitation_s: (end_us - 300_000 - start_us) / 1e6,
    samplesExpected: stamps.chipSamples,
    samplesReceived: last - firstSample,
    // gaps with received samples on both sides inside the window
    samplesLostReported: capture.gaps.filter((g) => g.kind === 'lost' && g.index > firstSample && g.index < last).reduce((n, g) => n + g.samples, 0),
  };
}
