/**
 * (b) A Blot-like pen plotter on one board (the paper's §4.3): one device runs
 * both CoreXY motors and the pen servo, so all its tracks share one clock.
 *
 * Firmware: firmware/examples/BlotPlotter (device "blot"; position readers
 * "a" on STEP D2 / DIR D5 and "b" on STEP D3 / DIR D6, 80 steps/mm; event
 * reader "pen" driving a servo on D9: 0 → 1000 µs pen up, 1 → 1900 µs down).
 */
import type { MachinePreset } from './presetTypes.ts';

export function blotPlotter(): MachinePreset {
  return {
    id: 'blotPlotter',
    description: 'Blot-like CoreXY pen plotter on one board: motors a, b and a pen servo on an event channel',
    config: {
      motionAxes: ['x', 'y'],
      eventChannels: ['pen'],
      limits: { maxVelocity: 120, maxAcceleration: 1500, junctionDeviation: 0.02 },
      transforms: [{ type: 'corexy', from: ['x', 'y'], to: ['a', 'b'] }],
      subscriptions: [
        { device: 'blot', track: 'a', reader: 'a' },
        { device: 'blot', track: 'b', reader: 'b' },
        { device: 'blot', track: 'pen', reader: 'pen' },
      ],
      softLimits: { x: [0, 125], y: [0, 125] },
    },
    devices: [
      {
        name: 'blot',
        example: 'BlotPlotter',
        readers: [
          { name: 'a', kind: 'position' },
          { name: 'b', kind: 'position' },
          { name: 'pen', kind: 'event' },
        ],
        clock: { offset_us: 2_718_281, ppm: -25 },
      },
    ],
    plant: {
      motors: [
        { device: 'blot', name: 'a', stepPin: 2, dirPin: 5, stepsPerMm: 80 },
        { device: 'blot', name: 'b', stepPin: 3, dirPin: 6, stepsPerMm: 80 },
      ],
      kinematics: { type: 'corexy', a: 'a', b: 'b', x: 'x', y: 'y' },
      // A small, stiff machine.
      spring: { naturalFrequency_hz: 70, damping: 0.12 },
      // An SG90-class servo swings ~60° in ~100 ms at 5 V; lifting fights the pen spring less.
      pen: { device: 'blot', pin: 9, upPulse_us: 1000, downPulse_us: 1900, dropDelay_us: 120_000, liftDelay_us: 90_000, tracePeriod_us: 1000, traceMinDistance_mm: 0.01 },
    },
  };
}
