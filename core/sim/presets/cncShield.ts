/**
 * (d) A three-axis machine on one Arduino Uno with a CNC shield (the board
 * GRBL drives): x, y and z steppers stepping from one timer interrupt, and a
 * spindle or laser whose PWM power is an event track (power per mm) scaled by
 * the velocity track (the paper's Listing 4).
 *
 * Firmware: firmware/examples/CncShield (device "cncShield"; position readers
 * "x" on STEP D2 / DIR D5, "y" on STEP D3 / DIR D6, "z" on STEP D4 / DIR D7,
 * 80 steps/mm; event reader "spindle" and velocity reader "velocity", the PWM
 * on D11). The plant models the motors and a Cartesian carriage; it does not
 * model the spindle (its PWM writes reach the simulator's pins only).
 */
import type { MachinePreset } from './presetTypes.ts';

export function cncShield(): MachinePreset {
  const device = 'cncShield';
  return {
    id: 'cncShield',
    description: 'Three-axis machine on an Uno with a CNC shield: steppers x, y, z and a spindle on an event channel scaled by the speed',
    config: {
      motionAxes: ['x', 'y', 'z'],
      eventChannels: ['spindle'],
      limits: { maxVelocity: 100, maxAcceleration: 1500, junctionDeviation: 0.02 },
      subscriptions: [
        { device, track: 'x', reader: 'x' },
        { device, track: 'y', reader: 'y' },
        { device, track: 'z', reader: 'z' },
        { device, track: 'spindle', reader: 'spindle' },
        { device, track: 'velocity', reader: 'velocity' },
      ],
      softLimits: { x: [0, 300], y: [0, 200], z: [0, 50] },
    },
    devices: [
      {
        name: device,
        example: 'CncShield',
        readers: [
          { name: 'x', kind: 'position' },
          { name: 'y', kind: 'position' },
          { name: 'z', kind: 'position' },
          { name: 'spindle', kind: 'event' },
          { name: 'velocity', kind: 'velocity' },
        ],
        clock: { offset_us: 1_414_213, ppm: 40 },
      },
    ],
    plant: {
      motors: [
        { device, name: 'x', stepPin: 2, dirPin: 5, stepsPerMm: 80 },
        { device, name: 'y', stepPin: 3, dirPin: 6, stepsPerMm: 80 },
        { device, name: 'z', stepPin: 4, dirPin: 7, stepsPerMm: 80 },
      ],
      kinematics: { type: 'direct', axes: { x: 'x', y: 'y', z: 'z' } },
      spring: { naturalFrequency_hz: 60, damping: 0.1 },
    },
  };
}
