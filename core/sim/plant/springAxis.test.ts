import { describe, expect, it } from 'vitest';
import { seededRandom } from '../../random.ts';
import { SpringAxis } from './springAxis.ts';
import type { SpringParameters } from './springResponse.ts';

/** Textbook unit-step response of an underdamped second-order system (tool starting at rest). */
function underdampedStep(delta: number, t_s: number, p: SpringParameters) {
  const w = 2 * Math.PI * p.naturalFrequency_hz;
  const z = p.damping;
  const wd = w * Math.sqrt(1 - z * z);
  const decay = Math.exp(-z * w * t_s);
  const phi = Math.acos(z);
  return {
    // x(t) = Δ·[1 − e^(−ζωt)/√(1−ζ²) · sin(ω_d t + φ)],  φ = arccos ζ
    x: delta * (1 - (decay / Math.sqrt(1 - z * z)) * Math.sin(wd * t_s + phi)),
    // v(t) = Δ·ω/√(1−ζ²) · e^(−ζωt) · sin(ω_d t)
    v: ((delta * w) / Math.sqrt(1 - z * z)) * decay * Math.sin(wd * t_s),
  };
}

/** An independent check: classic RK4 on x'' = ω²(u − x) − 2ζω x' with a small fixed step. */
function rk4(inputs: Array<[number, number]>, end_us: number, p: SpringParameters, dt_us = 1): { x: number; v: number } {
  const w = 2 * Math.PI * p.naturalFrequency_hz;
  const f = (x: number, v: number, u: number): [number, number] => [v, w * w * (u - x) - 2 * p.damping * w * v];
  let x = inputs[0][1];
  let v = 0;
  let k = 0;
  let u = inputs[0][1];
  for (let t = 0; t < end_us; t += dt_us) {
    while (k < inputs.length && inputs[k][0] <= t) u = inputs[k++][1];
    const h = dt_us * 1e-6;
    const [a1, b1] = f(x, v, u);
    const [a2, b2] = f(x + (h / 2) * a1, v + (h / 2) * b1, u);
    const [a3, b3] = f(x + (h / 2) * a2, v + (h / 2) * b2, u);
    const [a4, b4] = f(x + h * a3, v + h * b3, u);
    x += (h / 6) * (a1 + 2 * a2 + 2 * a3 + a4);
    v += (h / 6) * (b1 + 2 * b2 + 2 * b3 + b4);
  }
  return { x, v };
}

describe('SpringAxis (belt resonance)', () => {
  it('matches the closed-form underdamped step response, however it is advanced', () => {
    const p = { naturalFrequency_hz: 40, damping: 0.08 };
    const axis = new SpringAxis(p, 0, 0);
    axis.setCarriage(2, 1000);
    const random = seededRandom(5);
    let t = 1000;
    for (let i = 0; i < 300; i++) {
      t += Math.floor(random() * 2000); // irregular advances, including zero
      axis.advanceTo(t);
      const s = axis.stateAt(t);
      const want = underdampedStep(2, (t - 1000) * 1e-6, p);
      expect(s.position).toBeCloseTo(want.x, 9);
      expect(s.velocity).toBeCloseTo(want.v, 6);
      // Acceleration from the equation of motion.
      const w = 2 * Math.PI * 40;
      expect(s.acceleration).toBeCloseTo(w * w * (2 - want.x) - 2 * 0.08 * w * want.v, 3);
    }
    // The first overshoot peaks at t = π/ω_d with height Δ·e^(−ζπ/√(1−ζ²)).
    const wd = 2 * Math.PI * 40 * Math.sqrt(1 - 0.08 ** 2);
    const peak = axis.stateAt(1000 + (Math.PI / wd) * 1e6);
    expect(peak.position - 2).toBeCloseTo(2 * Math.exp((-0.08 * Math.PI) / Math.sqrt(1 - 0.08 ** 2)), 9);
    expect(peak.velocity).toBeCloseTo(0, 6);
  });

  it('is stable over any interval: one advance of 10 s lands at rest on the carriage', () => {
    const axis = new SpringAxis({ naturalFrequency_hz: 2000, damping: 0.01 }, 0, 0);
    axis.setCarriage(5, 0);
    axis.advanceTo(10_000_000);
    const s = axis.stateAt(10_000_000);
    expect(s.position).toBeCloseTo(5, 9);
    expect(s.velocity).toBeCloseTo(0, 6);
  });

  for (const damping of [0.05, 1, 2.5]) {
    it(`agrees with RK4 on a random staircase of carriage steps (ζ = ${damping})`, () => {
      const p = { naturalFrequency_hz: 35, damping };
      const axis = new SpringAxis(p, 0, 0);
      const random = seededRandom(11);
      const inputs: Array<[number, number]> = [[0, 0]];
      let u = 0;
      for (let t = 100; t < 60_000; t += 50 + Math.floor(random() * 400)) {
        u += 0.0125 * (random() < 0.7 ? 1 : -1);
        inputs.push([t, u]);
        axis.setCarriage(u, t);
      }
      axis.advanceTo(80_000);
      const got = axis.stateAt(80_000);
      const want = rk4(inputs, 80_000, p);
      expect(got.position).toBeCloseTo(want.x, 7);
      expect(got.velocity).toBeCloseTo(want.v, 4);
      // And the past is recomputed exactly from the checkpoints.
      const past = axis.stateAt(30_000);
      const wantPast = rk4(inputs, 30_000, p);
      expect(past.position).toBeCloseTo(wantPast.x, 7);
    });
  }

  it('refuses to answer for times older than the history it keeps', () => {
    const axis = new SpringAxis({ naturalFrequency_hz: 40, damping: 0.1 }, 0, 0, 8);
    for (let k = 1; k <= 20; k++) axis.setCarriage(k, k * 100);
    expect(() => axis.stateAt(500)).toThrow(RangeError);
    expect(axis.stateAt(1500).carriage).toBe(15);
  });
});
