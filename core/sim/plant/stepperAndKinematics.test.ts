import { describe, expect, it } from 'vitest';
import { resolveTransforms, actuatorPosition } from '../../config/transforms.ts';
import { seededRandom } from '../../random.ts';
import { carriagePositions } from './kinematics.ts';
import { Plant } from './plant.ts';
import { StepperMotor } from './stepperMotor.ts';

describe('StepperMotor', () => {
  it('counts rising STEP edges in the direction DIR holds, and ignores repeated levels', () => {
    const positions: number[] = [];
    const m = new StepperMotor({ name: 'a', stepPin: 2, dirPin: 5, stepsPerMm: 80 }, (p) => positions.push(p));
    let t = 0;
    const pulse = () => {
      m.pinWrite(2, 1, ++t);
      m.pinWrite(2, 1, ++t); // still high: not a new step
      m.pinWrite(2, 0, ++t);
    };
    m.pinWrite(5, 1, ++t);
    for (let i = 0; i < 10; i++) pulse();
    m.pinWrite(5, 0, ++t);
    for (let i = 0; i < 3; i++) pulse();
    expect(m.steps).toBe(7);
    expect(m.stepsForward).toBe(10);
    expect(m.stepsBackward).toBe(3);
    expect(m.position_mm).toBeCloseTo(7 / 80, 12);
    expect(positions.length).toBe(13);
    expect(m.pinWrite(9, 1, ++t)).toBe(false); // not its pin
  });

  it('honours inverted wiring and a power-up position', () => {
    const m = new StepperMotor({ name: 'x', stepPin: 3, dirPin: 6, stepsPerMm: 100, invertDirection: true, initialPosition_mm: 12 });
    m.pinWrite(6, 1, 1);
    m.pinWrite(3, 1, 2);
    m.pinWrite(3, 0, 3);
    expect(m.steps).toBe(-1);
    expect(m.position_mm).toBeCloseTo(11.99, 12);
  });
});

describe('CoreXY inverse kinematics', () => {
  it('gives x = (a+b)/2, y = (a−b)/2, the inverse of the core transform a = x+y, b = x−y', () => {
    const k = { type: 'corexy', a: 'a', b: 'b', x: 'x', y: 'y' } as const;
    const forward = resolveTransforms([{ type: 'corexy', from: ['x', 'y'], to: ['a', 'b'] }], ['x', 'y']);
    const random = seededRandom(3);
    for (let i = 0; i < 100; i++) {
      const x = (random() - 0.5) * 400;
      const y = (random() - 0.5) * 400;
      const [a, b] = actuatorPosition(forward, [x, y]);
      const back = carriagePositions(k, { a, b });
      expect(back.x).toBeCloseTo(x, 9);
      expect(back.y).toBeCloseTo(y, 9);
    }
  });

  it('moves the plant carriage by half a step on both axes for each step of one CoreXY motor', () => {
    const plant = new Plant(
      {
        motors: [
          { device: 'ma', name: 'a', stepPin: 2, dirPin: 5, stepsPerMm: 80 },
          { device: 'mb', name: 'b', stepPin: 2, dirPin: 5, stepsPerMm: 80 },
        ],
        kinematics: { type: 'corexy', a: 'a', b: 'b', x: 'x', y: 'y' },
        spring: { naturalFrequency_hz: 50, damping: 0.1 },
      },
      { seed: 1 },
    );
    const ha = plant.hardwareFor('ma');
    const hb = plant.hardwareFor('mb');
    let t = 0;
    const steps = (h: typeof ha, n: number) => {
      h.digitalWrite(5, n > 0 ? 1 : 0, (t += 10));
      for (let i = 0; i < Math.abs(n); i++) {
        h.digitalWrite(2, 1, (t += 10));
        h.digitalWrite(2, 0, (t += 10));
      }
    };
    steps(ha, 80); // a = 1 mm: x = 0.5, y = 0.5
    expect(plant.carriage()).toEqual({ x: 0.5, y: 0.5 });
    steps(hb, 160); // b = 2 mm: x = 1.5, y = −0.5
    expect(plant.carriage()).toEqual({ x: 1.5, y: -0.5 });
    steps(ha, -40); // a = 0.5 mm
    expect(plant.motorSteps()).toEqual({ a: 40, b: 160 });
    expect(plant.motorPositions()).toEqual({ a: 0.5, b: 2 });
    expect(plant.carriage()).toEqual({ x: 1.25, y: -0.75 });
    // The spring axes follow the carriage as their input.
    expect(plant.tool().x.carriage).toBe(1.25);
    expect(plant.tool().y.carriage).toBe(-0.75);
    // Each device only drives its own motor.
    expect(plant.motors.a.stepsForward).toBe(80);
    expect(plant.motors.b.stepsForward).toBe(160);
  });
});
