import { describe, expect, it } from 'vitest';
import { Plant } from './plant.ts';

describe('ToolTrace', () => {
  it('samples the tool’s true position, velocity and acceleration at a fixed period', () => {
    const plant = new Plant(
      {
        motors: [{ device: 'm', name: 'x', stepPin: 2, dirPin: 5, stepsPerMm: 1 }],
        kinematics: { type: 'direct', axes: { x: 'x' } },
        spring: { naturalFrequency_hz: 20, damping: 0.1 },
        toolTrace: { period_us: 1000 },
      },
      { seed: 1 },
    );
    const h = plant.hardwareFor('m');
    h.digitalWrite(5, 1, 10_500);
    h.digitalWrite(2, 1, 10_500); // a 1 mm step at 10.5 ms
    plant.advanceTo(100_000);
    const trace = plant.trace!;
    expect(trace.t_us.length).toBe(101); // 0, 1 ms, …, 100 ms
    expect(trace.t_us[37]).toBe(37_000);
    expect(trace.position.x.slice(0, 11).every((p) => p === 0)).toBe(true);
    expect(trace.position.x[11]).toBeGreaterThan(0);
    for (const k of [11, 20, 37, 64, 100]) {
      const truth = plant.tool(k * 1000).x;
      expect(trace.position.x[k]).toBeCloseTo(truth.position, 12);
      expect(trace.velocity.x[k]).toBeCloseTo(truth.velocity, 9);
      expect(trace.acceleration.x[k]).toBeCloseTo(truth.acceleration, 6);
    }
  });
});
