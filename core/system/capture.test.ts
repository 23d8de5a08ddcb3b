/**
 * The capture tool's claims on the simulated accelerometer rig, in virtual time, against
 * the simulator's ground truth (captureRun.ts):
 *  - every sample is stamped within 0.5 ms of the centre of the chip's averaging window;
 *  - a resonance sweep of under 60 s finds the belt's resonance within 1 %;
 *  - samples lost on the link are reported exactly, each gap as an event.
 */
import { describe, expect, it } from 'vitest';
import { runCaptureOnAccelRig } from './captureRun.ts';
import type { SampleGap } from '../capture/sensorCapture.ts';

describe('capture on the accelerometer rig', () => {
  it('a 50 s resonance sweep: stamps within 0.5 ms of the truth, the peak within 1 % of the resonance, nothing lost', async () => {
    const r = await runCaptureOnAccelRig({ kind: 'sweep', axis: 'x', fromHz: 10, toHz: 45, hzPerSecond: 0.7, accelPerHz: 60 }, 3);
    expect(r.excitation_s).toBeLessThanOrEqual(60);
    expect(r.stamps.unmatched).toBe(0);
    expect(r.stamps.matched).toBe(r.samplesReceived);
    expect(r.stamps.worst_us).toBeLessThan(500);
    expect(r.samplesReceived).toBeGreaterThan(4900);
    expect(r.samplesExpected).toBe(r.samplesReceived);
    expect(r.samplesLostReported).toBe(0);
    const error = Math.abs(r.analysis.peak!.frequency_hz - r.truePeak_hz) / r.truePeak_hz;
    expect(error).toBeLessThan(0.01);
    await r.bench.sim.stop();
  }, 120_000);

  for (const [seed, grow, from, to] of [
    [1, 'speed', 20, 150],
    [2, 'acceleration', 500, 3000],
  ] as const) {
    it(`strokes of growing ${grow} (seed ${seed}): stamps within 0.5 ms, no error`, async () => {
      const r = await runCaptureOnAccelRig({ kind: 'growing', axis: 'x', grow, stroke_mm: 20, from, to, steps: 4 }, seed);
      expect(r.bench.events.filter((e) => e.type === 'error')).toEqual([]);
      expect(r.stamps.unmatched).toBe(0);
      expect(r.stamps.matched).toBeGreaterThan(100);
      expect(r.stamps.worst_us).toBeLessThan(500);
      await r.bench.sim.stop();
    }, 120_000);
  }

  it('samples lost to a corrupted link are reported exactly, one event per gap', async () => {
    const gaps: SampleGap[] = [];
    const r = await runCaptureOnAccelRig(
      { kind: 'sweep', axis: 'x', fromHz: 20, toHz: 35, hzPerSecond: 3, accelPerHz: 60 },
      5,
      { links: { accelerometer: { toAuthor: { corruptionProbability: 3e-3 } } } },
      (gap) => gaps.push(gap),
    );
    // Some frames were lost, and every lost sample is accounted for: the board took
    // (chip reads, ground truth) exactly what arrived plus what was reported lost.
    expect(r.samplesLostReported).toBeGreaterThan(0);
    expect(r.samplesReceived + r.samplesLostReported).toBe(r.samplesExpected);
    // At the example's rate, 1 kHz (at least 500 Hz over the Uno's UART): the board's samples
    // (received and lost) over the span of the stamps received.
    const times = r.capture.timeColumn();
    const span_s = (times[r.firstSample + r.samplesReceived - 1] - times[r.firstSample]) / 1e6;
    expect((r.samplesExpected - 1) / span_s).toBeGreaterThan(990);
    expect((r.samplesExpected - 1) / span_s).toBeLessThan(1010);
    const during = gaps.filter((g) => g.kind === 'lost' && g.index > r.firstSample && g.index < r.firstSample + r.samplesReceived);
    expect(during.length).toBeGreaterThan(5);
    expect(during.reduce((n, g) => n + g.samples, 0)).toBe(r.samplesLostReported);
    // Each gap kept by the capture since the listener was added came as one event.
    expect(gaps).toEqual(r.capture.gaps.slice(-gaps.length));
    // The sample numbers jump by exactly the samples lost at each gap.
    const seq = r.capture.sequenceColumn();
    for (const g of during) expect(seq[g.index] - seq[g.index - 1]).toBe(g.samples + 1);
    await r.bench.sim.stop();
  }, 120_000);
});
