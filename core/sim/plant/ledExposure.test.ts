import { describe, expect, it } from 'vitest';
import { LedExposure } from './ledExposure.ts';
import { Plant } from './plant.ts';

const image = { width: 100, height: 50, mmPerPixel: 0.5, origin_mm: [0, 0] as [number, number], maxStep_us: 100 };

describe('LedExposure', () => {
  it('accumulates colour × dwell time at the LED’s position', () => {
    const leds = new LedExposure({ count: 1, origin_mm: [0, 0], pitch_mm: [0, 1] }, image);
    leds.show(Uint8Array.of(255, 10, 0));
    leds.expose(0, 10_000, () => [5, 2.5]); // pixel (10, 5), 10 ms
    const p = 3 * (5 * 100 + 10);
    expect(leds.image[p]).toBeCloseTo(2.55, 5);
    expect(leds.image[p + 1]).toBeCloseTo(0.1, 6);
    expect(leds.image[p + 2]).toBe(0);
    // Dark LEDs add nothing.
    leds.show(new Uint8Array(3));
    leds.expose(10_000, 20_000, () => [5, 2.5]);
    expect(leds.image[p]).toBeCloseTo(2.55, 5);
    expect(leds.image.reduce((a, b) => a + b, 0)).toBeCloseTo(2.65, 4);
  });

  it('spreads a moving LED evenly along its path, each LED at its offset along the strip', () => {
    const leds = new LedExposure({ count: 3, origin_mm: [0, 1], pitch_mm: [0, 2] }, image);
    // LED 0 white, LED 1 off, LED 2 blue.
    leds.show(Uint8Array.of(255, 255, 255, 0, 0, 0, 0, 0, 255));
    // The tool sweeps x from 5 to 45 mm at 100 mm/s (0.4 s) along y = 10.
    leds.expose(0, 400_000, (t) => [5 + 100 * t * 1e-6, 10]);
    const at = (i: number, j: number, c: number) => leds.image[3 * (j * 100 + i) + c];
    // LED 0 at y = 11 mm (row 22), LED 2 at y = 15 mm (row 30); nothing on LED 1's row 26.
    // Each 0.5 mm pixel is crossed in 5 ms: 255 × 0.005 = 1.275 per pixel, away from the ends.
    for (let i = 20; i <= 80; i += 7) {
      expect(at(i, 22, 0)).toBeCloseTo(1.275, 3);
      expect(at(i, 30, 2)).toBeCloseTo(1.275, 3);
      expect(at(i, 30, 0)).toBe(0);
      expect(at(i, 26, 0)).toBe(0);
    }
    // Total exposure is colour × time, whatever the path.
    let red = 0;
    for (let k = 0; k < leds.image.length; k += 3) red += leds.image[k];
    expect(red).toBeCloseTo(255 * 0.4, 2);
  });

  it('deposits each sub-interval at its middle, so the light’s centroid is the time-average position', () => {
    // Sub-intervals of up to 10 ms; the tool goes from x = 10 to 11 mm in 10 ms.
    const leds = new LedExposure({ count: 1, origin_mm: [0, 0], pitch_mm: [0, 1] }, { ...image, maxStep_us: 10_000 });
    leds.show(Uint8Array.of(100, 0, 0));
    leds.expose(0, 10_000, (t) => [10 + t * 1e-4, 5]);
    let sum = 0;
    let moment = 0;
    for (let i = 0; i < 100; i++) {
      const r = leds.image[3 * (10 * 100 + i)];
      sum += r;
      moment += r * i * 0.5;
    }
    expect(sum).toBeCloseTo(1, 6);
    expect(moment / sum).toBeCloseTo(10.5, 6);
  });

  it('counts light that falls outside the image', () => {
    const leds = new LedExposure({ count: 1, origin_mm: [0, 0], pitch_mm: [1, 0] }, image);
    leds.show(Uint8Array.of(100, 0, 0));
    leds.expose(0, 1_000_000, () => [-20, 10]);
    expect(leds.outside[0]).toBeCloseTo(100, 6);
    expect(leds.image.every((v) => v === 0)).toBe(true);
  });

  it('exposes through the plant between LED updates, at the tool position', () => {
    const plant = new Plant(
      {
        motors: [{ device: 'm', name: 'x', stepPin: 2, dirPin: 5, stepsPerMm: 1 }],
        kinematics: { type: 'direct', axes: { x: 'x' } },
        spring: { naturalFrequency_hz: 40, damping: 0.2 },
        ledStrip: { device: 'strip', pin: 6, strip: { count: 1, origin_mm: [0, 0], pitch_mm: [0, 1] }, image },
      },
      { seed: 1 },
    );
    const strip = plant.hardwareFor('strip');
    strip.ledShow(6, Uint8Array.of(0, 200, 0), 1000);
    strip.ledShow(6, Uint8Array.of(0, 0, 0), 51_000); // 50 ms at (0, 0)
    strip.ledShow(7, Uint8Array.of(255, 255, 255), 52_000); // another pin: not the strip
    plant.advanceTo(100_000);
    expect(plant.leds?.image[1]).toBeCloseTo(200 * 0.05, 4);
    expect(plant.leds?.image.reduce((a, b) => a + b, 0)).toBeCloseTo(10, 4);
  });
});
