/**
 * (a) The paper's light painter (§4.1, Figure 1): a CoreXY gantry, each motor
 * on its own Stepper board, and an 8-LED NeoPixel strip on the tool reading
 * an 8-bit event channel, one bit per LED. A long exposure shows what the
 * event evaluator wrote in light.
 *
 * Firmware: firmware/examples/Stepper (device "motorOne", reader "stepper",
 * STEP D2, DIR D5, 80 steps/mm) twice, renamed "motorA" and "motorB"; and
 * firmware/examples/LightPainter (device "lightPainter", strip on D6): event
 * readers "neopixelBitmap" (one bit per LED), "neopixelColour" (0xRRGGBB of a
 * lit LED at cruise, (255, 60, 10) until set) and "neopixelCruise" (mm/s), and
 * a velocity reader that dims the strip by v / cruise, so light per mm stays
 * even through the ramps (the paper's Listing 4, for LEDs).
 */
import type { MachinePreset } from './presetTypes.ts';

/** Spacing of the strip's LEDs along y, mm (a NeoPixel Stick: 8 LEDs in 51 mm). */
export const LIGHT_PAINTER_LED_PITCH_MM = 6.4;

export function lightPainter(): MachinePreset {
  const stepper = { stepPin: 2, dirPin: 5, stepsPerMm: 80 };
  return {
    id: 'lightPainter',
    description: 'CoreXY light painter: motors a and b on two Stepper boards, an 8-LED strip on an 8-bit event channel',
    config: {
      motionAxes: ['x', 'y'],
      eventChannels: ['neopixelBitmap', 'neopixelColour', 'neopixelCruise'],
      limits: { maxVelocity: 200, maxAcceleration: 2000, junctionDeviation: 0.05 },
      transforms: [{ type: 'corexy', from: ['x', 'y'], to: ['a', 'b'] }],
      subscriptions: [
        { device: 'motorA', track: 'a', reader: 'stepper' },
        { device: 'motorB', track: 'b', reader: 'stepper' },
        { device: 'lightPainter', track: 'neopixelBitmap', reader: 'neopixelBitmap' },
        { device: 'lightPainter', track: 'neopixelColour', reader: 'neopixelColour' },
        { device: 'lightPainter', track: 'neopixelCruise', reader: 'neopixelCruise' },
        { device: 'lightPainter', track: 'velocity', reader: 'velocity' },
      ],
      softLimits: { x: [0, 300], y: [0, 200] },
    },
    devices: [
      { name: 'motorA', example: 'Stepper', firmwareName: 'motorOne', readers: [{ name: 'stepper', kind: 'position' }], clock: { offset_us: 12_345_678, ppm: 35 } },
      // Starts 21 minutes before its 32-bit wrap: an hour-long job crosses it.
      { name: 'motorB', example: 'Stepper', firmwareName: 'motorOne', readers: [{ name: 'stepper', kind: 'position' }], clock: { offset_us: 3_000_000_000, ppm: -60 } },
      { name: 'lightPainter', example: 'LightPainter', readers: [
          { name: 'neopixelBitmap', kind: 'event' },
          { name: 'neopixelColour', kind: 'event' },
          { name: 'neopixelCruise', kind: 'event' },
          { name: 'velocity', kind: 'velocity' },
        ], clock: { offset_us: 987_654, ppm: 120 } },
    ],
    plant: {
      motors: [
        { device: 'motorA', name: 'a', ...stepper },
        { device: 'motorB', name: 'b', ...stepper },
      ],
      kinematics: { type: 'corexy', a: 'a', b: 'b', x: 'x', y: 'y' },
      spring: { naturalFrequency_hz: 45, damping: 0.08 },
      ledStrip: {
        device: 'lightPainter',
        pin: 6,
        // Across the direction of writing, centred on the tool.
        strip: { count: 8, origin_mm: [0, -3.5 * LIGHT_PAINTER_LED_PITCH_MM], pitch_mm: [0, LIGHT_PAINTER_LED_PITCH_MM] },
        // The 300 × 200 mm bed and a margin for the strip, at 0.5 mm per pixel.
        image: { width: 640, height: 480, mmPerPixel: 0.5, origin_mm: [-10, -40], maxStep_us: 200 },
      },
    },
  };
}
