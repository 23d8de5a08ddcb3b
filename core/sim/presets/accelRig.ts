/**
 * (c) The paper's accelerometer demonstration (§4.2, Figure 7): one axis, x,
 * on a Stepper board, and a BNO055 on the tool read by its own board, which
 * stamps each sample with its clock so the author can lay measured over
 * planned acceleration. The belt is soft enough to ring visibly.
 *
 * Firmware: firmware/examples/Stepper (device "motorOne", reader "stepper",
 * STEP D2, DIR D5, 80 steps/mm) and firmware/examples/Accelerometer (device
 * "accelerometer", sensor reader "accel" with 3 channels, mm/s², a sample
 * every 1 ms; BNO055 at 0x28 in ACCONLY mode).
 *
 * The sensor reader is not in the config's subscriptions: MaxlConfig
 * subscribes readers to tracks, and a sensor reader reads no track. How the
 * runtime subscribes it (to capture its samples) is the runtime's business.
 */
import type { MachinePreset } from './presetTypes.ts';

export function accelRig(): MachinePreset {
  return {
    id: 'accelRig',
    description: 'Accelerometer rig: an x stepper board and a BNO055 board on the tool',
    config: {
      motionAxes: ['x'],
      limits: { maxVelocity: 150, maxAcceleration: 3000, junctionDeviation: 0.05 },
      subscriptions: [{ device: 'motorOne', track: 'x', reader: 'stepper' }],
      softLimits: { x: [0, 300] },
    },
    devices: [
      { name: 'motorOne', example: 'Stepper', readers: [{ name: 'stepper', kind: 'position' }], clock: { offset_us: 55_555, ppm: 80 } },
      // Wraps 46 minutes in. (Below 2³¹ at power-up: the example's first-sample
      // test, (int32_t)(micros() − 0) < period, holds for up to 36 minutes on a
      // board whose counter starts above 2³¹; see core/sim/README.md.)
      { name: 'accelerometer', example: 'Accelerometer', readers: [{ name: 'accel', kind: 'sensor' }], clock: { offset_us: 1_500_000_000, ppm: -110 } },
    ],
    plant: {
      motors: [{ device: 'motorOne', name: 'x', stepPin: 2, dirPin: 5, stepsPerMm: 80 }],
      kinematics: { type: 'direct', axes: { x: 'x' } },
      spring: { naturalFrequency_hz: 28, damping: 0.06 },
      accelerometer: { device: 'accelerometer', address: 0x28, noiseDensity_ug: 150, recordSamples: true },
    },
  };
}
