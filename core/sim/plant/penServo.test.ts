import { describe, expect, it } from 'vitest';
import { Plant } from './plant.ts';
import { PenServo } from './penServo.ts';

const pen = { pin: 9, upPulse_us: 1000, downPulse_us: 2000, dropDelay_us: 80_000, liftDelay_us: 120_000, tracePeriod_us: 1000, traceMinDistance_mm: 0.001 };

describe('PenServo', () => {
  it('lands the pen a drop delay after a down pulse and lifts it a lift delay after an up pulse', () => {
    const s = new PenServo(pen);
    const still = () => [0, 0] as [number, number];
    s.pulse(1900, 10_000); // nearer 2000: down
    s.advance(0, 89_999, still);
    expect(s.isDown).toBe(false);
    s.advance(89_999, 90_000, still);
    expect(s.isDown).toBe(true);
    s.pulse(1100, 200_000); // up
    s.advance(90_000, 319_999, still);
    expect(s.isDown).toBe(true);
    s.advance(319_999, 400_000, still);
    expect(s.isDown).toBe(false);
    expect(s.transitions).toEqual([
      { t_us: 90_000, down: true },
      { t_us: 320_000, down: false },
    ]);
    expect(s.isDownAt(100_000)).toBe(true);
    expect(s.isDownAt(330_000)).toBe(false);
  });

  it('cancels a swing reversed before it lands, and ignores repeats and detach (0)', () => {
    const s = new PenServo(pen);
    const still = () => [0, 0] as [number, number];
    s.pulse(2000, 0);
    s.pulse(2000, 10_000); // a repeat does not restart the swing
    s.pulse(1000, 50_000); // reversed before 80 ms
    s.pulse(0, 60_000);
    s.advance(0, 1_000_000, still);
    expect(s.transitions).toEqual([]);
    s.pulse(2000, 1_000_000);
    s.advance(1_000_000, 2_000_000, still);
    expect(s.transitions).toEqual([{ t_us: 1_080_000, down: true }]);
  });

  it('records the tool path while the pen is down, through the plant', () => {
    const plant = new Plant(
      {
        motors: [{ device: 'blot', name: 'x', stepPin: 2, dirPin: 5, stepsPerMm: 10 }],
        kinematics: { type: 'direct', axes: { x: 'x' } },
        spring: { naturalFrequency_hz: 200, damping: 0.7 },
        pen: { device: 'blot', ...pen },
      },
      { seed: 1 },
    );
    const h = plant.hardwareFor('blot');
    h.servoPulse(9, 2000, 0);
    h.digitalWrite(5, 1, 0);
    // 100 steps of 0.1 mm, one every 2 ms, from 100 ms: x goes 0 → 10 mm.
    for (let k = 0; k < 100; k++) {
      h.digitalWrite(2, 1, 100_000 + 2000 * k);
      h.digitalWrite(2, 0, 100_000 + 2000 * k + 5);
    }
    h.servoPulse(9, 1000, 400_000);
    plant.advanceTo(1_000_000);
    const strokes = plant.pen?.strokes ?? [];
    expect(strokes.length).toBe(1);
    const [stroke] = strokes;
    expect(stroke.t_us[0]).toBe(80_000);
    expect(stroke.t_us[stroke.t_us.length - 1]).toBe(520_000);
    expect(stroke.x[0]).toBeCloseTo(0, 9);
    expect(stroke.x[stroke.x.length - 1]).toBeCloseTo(10, 3);
    // Points follow the true tool path.
    stroke.t_us.forEach((t, i) => expect(stroke.x[i]).toBeCloseTo(plant.tool(t).x.position, 12));
    expect(new Set(stroke.x.map((x) => x.toFixed(2))).size).toBeGreaterThan(100);
    // No points are added while the pen rests down without moving (after 300 ms + settling).
    expect(stroke.t_us.filter((t) => t > 400_000).length).toBeLessThan(5);
  });
});
