import { describe, expect, it } from 'vitest';
import { Plant } from './plant.ts';
import { Bno055, Bno055Register as R, BNO055_ADDRESS } from './bno055.ts';
import { seededRandom } from '../../random.ts';
import type { PlantConfig } from './plantConfig.ts';

const G = 9.80665;

function rig(noiseDensity_ug: number): Plant {
  const config: PlantConfig = {
    motors: [{ device: 'motor', name: 'x', stepPin: 2, dirPin: 5, stepsPerMm: 1 }],
    kinematics: { type: 'direct', axes: { x: 'x' } },
    spring: { naturalFrequency_hz: 30, damping: 0.1 },
    accelerometer: { device: 'imu', address: BNO055_ADDRESS, noiseDensity_ug, recordSamples: true },
  };
  return new Plant(config, { seed: 99 });
}

/** Reads the 6 ACC_DATA bytes as a Wire-using sketch would: write the register, then read. */
function readAccel(h: ReturnType<Plant['hardwareFor']>, t: number, reg: number = R.ACC_DATA_X_LSB): [number, number, number] {
  expect(h.i2cWrite(BNO055_ADDRESS, Uint8Array.of(reg), t)).toBe(0);
  const b = h.i2cRead(BNO055_ADDRESS, 6, t) as Uint8Array;
  const view = new DataView(b.buffer);
  return [view.getInt16(0, true), view.getInt16(2, true), view.getInt16(4, true)];
}

const mean = (xs: number[]) => xs.reduce((a, b) => a + b, 0) / xs.length;
const std = (xs: number[]) => Math.sqrt(mean(xs.map((x) => (x - mean(xs)) ** 2)));

describe('BNO055 register model', () => {
  it('answers at its address with its chip id, and NACKs other addresses', () => {
    const h = rig(150).hardwareFor('imu');
    expect(h.i2cWrite(BNO055_ADDRESS, Uint8Array.of(R.CHIP_ID), 0)).toBe(0);
    expect([...(h.i2cRead(BNO055_ADDRESS, 4, 0) as Uint8Array)]).toEqual([0xa0, 0xfb, 0x32, 0x0f]);
    expect(h.i2cWrite(0x29, Uint8Array.of(0), 0)).toBe(2);
    expect(h.i2cRead(0x29, 1, 0)).toBeNull();
    // A device without the accelerometer gets no answer either.
    expect(rig(150).hardwareFor('motor').i2cRead(BNO055_ADDRESS, 1, 0)).toBeNull();
  });

  it('reads zeros in CONFIG mode, then gravity on z in ACCONLY mode, in m/s² (100 LSB) or mg (1 LSB)', () => {
    const h = rig(0).hardwareFor('imu');
    expect(readAccel(h, 1000)).toEqual([0, 0, 0]);
    h.i2cWrite(BNO055_ADDRESS, Uint8Array.of(R.OPR_MODE, 0x01), 2000);
    expect(readAccel(h, 3000)).toEqual([0, 0, Math.round(G * 100)]);
    h.i2cWrite(BNO055_ADDRESS, Uint8Array.of(R.UNIT_SEL, 0x01), 4000);
    expect(readAccel(h, 5000)).toEqual([0, 0, 1000]);
    // No linear acceleration output outside fusion modes; in NDOF, gravity is separated out.
    expect(readAccel(h, 5000, R.LIA_DATA_X_LSB)).toEqual([0, 0, 0]);
    h.i2cWrite(BNO055_ADDRESS, Uint8Array.of(R.OPR_MODE, 0x00), 6000);
    h.i2cWrite(BNO055_ADDRESS, Uint8Array.of(R.OPR_MODE, 0x0c), 7000);
    expect(readAccel(h, 20_000, R.GRV_DATA_X_LSB)).toEqual([0, 0, 1000]);
    expect(readAccel(h, 20_000, R.LIA_DATA_X_LSB)).toEqual([0, 0, 0]);
  });

  it('takes range and bandwidth from page 1 ACC_Config (only writable in CONFIG mode), and clips to the range', () => {
    const chip = new Bno055({ address: BNO055_ADDRESS, noiseDensity_ug: 0 }, () => [100, -100, G], seededRandom(1));
    expect(chip.range_g).toBe(4);
    expect(chip.bandwidth_hz).toBe(62.5);
    // page 1, ACC_Config = ±2 g, 1000 Hz (0b111_00)
    chip.i2cWrite(BNO055_ADDRESS, Uint8Array.of(R.PAGE_ID, 1));
    chip.i2cWrite(BNO055_ADDRESS, Uint8Array.of(R.ACC_CONFIG, 0x1c));
    chip.i2cWrite(BNO055_ADDRESS, Uint8Array.of(R.PAGE_ID, 0));
    expect(chip.range_g).toBe(2);
    expect(chip.samplePeriod_us).toBe(500);
    chip.i2cWrite(BNO055_ADDRESS, Uint8Array.of(R.OPR_MODE, 0x01));
    chip.i2cWrite(BNO055_ADDRESS, Uint8Array.of(R.ACC_DATA_X_LSB));
    const b = chip.i2cRead(BNO055_ADDRESS, 6, 0) as Uint8Array;
    const v = new DataView(b.buffer);
    expect([v.getInt16(0, true), v.getInt16(2, true), v.getInt16(4, true)]).toEqual([Math.round(2 * G * 100), -Math.round(2 * G * 100), Math.round(G * 100)]);
    // Outside CONFIG mode, the sensor config is locked.
    chip.i2cWrite(BNO055_ADDRESS, Uint8Array.of(R.PAGE_ID, 1));
    chip.i2cWrite(BNO055_ADDRESS, Uint8Array.of(R.ACC_CONFIG, 0x0d));
    expect(chip.range_g).toBe(2);
  });

  it('adds Gaussian noise of density·√bandwidth per axis, holding each sample for its period', () => {
    // 1500 µg/√Hz at 62.5 Hz: σ = 1500e-6 · 9.80665 · √62.5 ≈ 0.1163 m/s² ≈ 11.6 LSB.
    const plant = rig(1500);
    const h = plant.hardwareFor('imu');
    h.i2cWrite(BNO055_ADDRESS, Uint8Array.of(R.OPR_MODE, 0x01), 0);
    const chip = plant.accelerometer as Bno055;
    expect(chip.samplePeriod_us).toBe(8000); // 2 × 62.5 Hz
    const xs: number[] = [];
    const zs: number[] = [];
    for (let k = 1; k <= 4000; k++) {
      const a = readAccel(h, k * 8000 + 100);
      // Read again within the same sample period: the same sample.
      expect(readAccel(h, k * 8000 + 7900)).toEqual(a);
      xs.push(a[0]);
      zs.push(a[2]);
    }
    const sigmaLsb = 1500e-6 * G * Math.sqrt(62.5) * 100;
    expect(Math.abs(mean(xs))).toBeLessThan((4 * sigmaLsb) / Math.sqrt(4000));
    expect(Math.abs(mean(zs) - G * 100)).toBeLessThan((4 * sigmaLsb) / Math.sqrt(4000));
    // σ of a 4000-sample estimate is known to ~1.1 % (1/√(2n)); rounding to LSBs adds 1/12 LSB².
    expect(Math.abs(std(xs) / Math.sqrt(sigmaLsb ** 2 + 1 / 12) - 1)).toBeLessThan(0.05);
    expect(chip.samplesTaken.length).toBe(4000);
  });

  it('measures the tool’s mean acceleration over each sample period while the belt rings', () => {
    const plant = rig(0);
    const imu = plant.hardwareFor('imu');
    const motor = plant.hardwareFor('motor');
    imu.i2cWrite(BNO055_ADDRESS, Uint8Array.of(R.OPR_MODE, 0x01), 0);
    // One 1 mm step at t = 10 ms rings the 30 Hz belt.
    motor.digitalWrite(5, 1, 10_000);
    motor.digitalWrite(2, 1, 10_000);
    const chip = plant.accelerometer as Bno055;
    for (let k = 2; k < 40; k++) {
      const t = k * 8000 + 50;
      const [ax] = readAccel(imu, t);
      const sampleT = k * 8000;
      // Mean acceleration over [t − T, t] is Δv / T, from the exact tool velocity.
      const want = ((plant.tool(sampleT).x.velocity - plant.tool(sampleT - 8000).x.velocity) / 0.008) * 1e-3;
      expect(chip.samplesTaken[chip.samplesTaken.length - 1].truth[0]).toBeCloseTo(want, 9);
      expect(ax).toBe(Math.round(want * 100));
    }
    // The ringing is real: the sampled acceleration reached several m/s².
    expect(Math.max(...chip.samplesTaken.map((s) => Math.abs(s.accel[0])))).toBeGreaterThan(5);
  });
});
