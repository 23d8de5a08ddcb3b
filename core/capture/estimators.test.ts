/**
 * The spectrum and lag estimators on synthetic signals with a known answer.
 */
import { describe, expect, it } from 'vitest';
import { analyseCapture, resampleOnGrid } from './analysis.ts';
import { crossCorrelationLag, rmsDifference } from './lag.ts';
import { amplitudeSpectrum, fft, smoothSpectrum, spectrumPeak } from './spectrum.ts';
import { seededRandom, gaussian } from '../random.ts';

describe('fft', () => {
  it('equals the plain DFT sum', () => {
    const random = seededRandom(7);
    const n = 64;
    const x = Array.from({ length: n }, () => random() - 0.5);
    const re = Float64Array.from(x);
    const im = new Float64Array(n);
    fft(re, im);
    for (let k = 0; k < n; k++) {
      let sr = 0;
      let si = 0;
      for (let t = 0; t < n; t++) {
        sr += x[t] * Math.cos((-2 * Math.PI * k * t) / n);
        si += x[t] * Math.sin((-2 * Math.PI * k * t) / n);
      }
      expect(re[k]).toBeCloseTo(sr, 10);
      expect(im[k]).toBeCloseTo(si, 10);
    }
  });

  it('refuses a length that is not a power of two', () => {
    expect(() => fft(new Float64Array(6), new Float64Array(6))).toThrow(/power of two/);
  });
});

describe('spectrum peak', () => {
  // Tones between bins, at 100 Hz sampling, for 10 s (bins of 0.1 Hz before padding).
  for (const f of [7.77, 27.9, 28.03, 41.234]) {
    it(`finds a ${f} Hz tone to 0.01 % (1 % is the target), with noise and a strong 2 Hz drive beside it`, () => {
      const random = seededRandom(Math.round(f * 1000));
      const fs = 100;
      const x = Array.from({ length: 1000 }, (_, n) => {
        const t = n / fs;
        return 3 * Math.sin(2 * Math.PI * f * t + 0.3) + 20 * Math.sin(2 * Math.PI * 2 * t) + 0.5 * gaussian(random);
      });
      const peak = spectrumPeak(amplitudeSpectrum(x, fs), 5, 50)!;
      expect(Math.abs(peak.frequency_hz - f) / f).toBeLessThan(1e-4);
      expect(peak.amplitude).toBeGreaterThan(2.7);
      expect(peak.amplitude).toBeLessThan(3.3);
    });
  }

  it('finds the resonance of a damped oscillator from its impulse responses', () => {
    // x'' + 2ζω x' + ω² x = 0 rung every second: the spectrum's peak is near the damped
    // frequency ω√(1 − ζ²). Rung once a second, the record is periodic and its spectrum
    // is made of lines 1 Hz apart under the response's peak, so the peak found is the
    // line nearest it: within 0.5 Hz, 0.2 % here.
    const f0 = 28;
    const zeta = 0.06;
    const w = 2 * Math.PI * f0;
    const wd = w * Math.sqrt(1 - zeta * zeta);
    const fs = 100;
    const x = Array.from({ length: 6000 }, (_, n) => {
      const t = (n / fs) % 1;
      return Math.exp(-zeta * w * t) * Math.cos(wd * t);
    });
    const peak = spectrumPeak(amplitudeSpectrum(x, fs), 5, 50)!;
    expect(Math.abs(peak.frequency_hz - wd / (2 * Math.PI))).toBeLessThan(0.5);
    expect(Math.abs(peak.frequency_hz - 28)).toBeLessThan(1e-3);
  });

  it("smoothing keeps a tone's peak where it was, and conserves power", () => {
    const fs = 100;
    const x = Array.from({ length: 3000 }, (_, n) => Math.sin(2 * Math.PI * 27.9 * (n / fs)));
    const raw = amplitudeSpectrum(x, fs);
    const smooth = smoothSpectrum(raw, 0.3);
    expect(Math.abs(spectrumPeak(smooth, 5, 50)!.frequency_hz - 27.9)).toBeLessThan(0.02); // 0.07 %
    // Power is conserved by a moving mean (away from the ends).
    const power = (a: Float64Array) => a.reduce((s, v) => s + v * v, 0);
    expect(power(smooth.amplitude) / power(raw.amplitude)).toBeCloseTo(1, 3);
    // A spike one bin wide is spread over the window: its top falls by √(window bins).
    const spike = { ...raw, amplitude: new Float64Array(raw.amplitude.length) };
    spike.amplitude[1000] = 1;
    const bins = 2 * Math.round(0.3 / raw.binHz) + 1;
    expect(smoothSpectrum(spike, 0.3).amplitude[1000]).toBeCloseTo(1 / Math.sqrt(bins), 12);
  });

  it('says when there is nothing to look at', () => {
    expect(spectrumPeak(amplitudeSpectrum(new Array(16).fill(1), 100), 5, 50)).toBeNull();
    expect(() => amplitudeSpectrum([1, 2], 100)).toThrow(/at least 4/);
  });
});

describe('lag', () => {
  for (const lag_ms of [0, 3.3, -7.25, 12.6]) {
    it(`finds a lag of ${lag_ms} ms of a band-limited signal to 0.1 ms`, () => {
      const fs = 100;
      const signal = (t: number) => Math.sin(2 * Math.PI * 3 * t) + 0.5 * Math.sin(2 * Math.PI * 7.3 * t + 1) + 0.2 * Math.sin(2 * Math.PI * 1.1 * t);
      const planned = Array.from({ length: 2000 }, (_, n) => signal(n / fs));
      const measured = Array.from({ length: 2000 }, (_, n) => 2 * signal(n / fs - lag_ms / 1000) + 5);
      const est = crossCorrelationLag(planned, measured, 1 / fs, 0.1)!;
      expect(Math.abs(est.lag_s * 1000 - lag_ms)).toBeLessThan(0.1);
      expect(est.correlation).toBeGreaterThan(0.99);
    });
  }

  it('leaves out points marked invalid, and RMS counts only valid ones', () => {
    const planned = [0, 1, 0, -1, 0, 1, 0, -1, 0, 1, 0, -1];
    const measured = [...planned];
    measured[5] = 100;
    const valid = planned.map((_, i) => i !== 5);
    expect(crossCorrelationLag(planned, measured, 0.01, 0.02, valid)!.lag_s).toBeCloseTo(0, 9);
    expect(rmsDifference(planned, measured, valid)).toBe(0);
    expect(rmsDifference([0, 0], [3, 4])).toBeCloseTo(Math.sqrt(12.5), 12);
  });
});

describe('analyseCapture', () => {
  it('puts samples on a uniform grid and never bridges a gap', () => {
    const times = [0, 10, 20, 30, 80, 90, 100, 110];
    const g = resampleOnGrid({ times_us: times, measured: times.map((t) => t / 10), gapsBefore: [4], planned: () => 0 });
    expect(Array.from(g.grid_us)).toEqual([0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110]);
    expect(Array.from(g.valid)).toEqual([1, 1, 1, 1, 0, 0, 0, 0, 1, 1, 1, 1]);
    expect(g.measured[9]).toBe(9);
  });

  it('reads back a known lag, error and tone from stamped samples', () => {
    const fs = 100;
    const times = Array.from({ length: 3000 }, (_, n) => n * 1e4 + 1234.5);
    const planned = (t_us: number) => 1000 * Math.sin(2 * Math.PI * 2 * (t_us / 1e6));
    const measured = times.map((t) => planned(t - 8000) + 200 * Math.sin(2 * Math.PI * 31.4 * (t / 1e6)));
    const a = analyseCapture({ times_us: times, measured, planned, fMin_hz: 10 });
    expect(a.sampleRate_hz).toBeCloseTo(fs, 9);
    expect(a.lag!.lag_s * 1000).toBeCloseTo(8, 0);
    expect(Math.abs(a.peak!.frequency_hz - 31.4)).toBeLessThan(0.01);
    expect(a.rmsError).toBeGreaterThan(100);
  });
});
