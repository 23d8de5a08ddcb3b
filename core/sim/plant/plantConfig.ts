/**
 * What a simulated machine's physical side is: motors on device pins, the
 * kinematics from motors to the carriage, the belt spring to the tool, and the
 * tool's instruments. All positions in mm, times in author µs.
 */
import type { Kinematics } from './kinematics.ts';
import type { ExposureImageConfig, LedStripConfig } from './ledExposure.ts';
import type { PenServoConfig } from './penServo.ts';
import type { SpringParameters } from './springResponse.ts';
import type { StepperMotorConfig } from './stepperMotor.ts';

export interface PlantConfig {
  /** Each motor, on the step/dir pins of one device. */
  motors: Array<StepperMotorConfig & { device: string }>;
  kinematics: Kinematics;
  /** The belt spring between carriage and tool, per Cartesian axis, or one for all. */
  spring: SpringParameters | Record<string, SpringParameters>;
  /** An accelerometer on the tool, read over I2C by `device`. */
  accelerometer?: {
    device: string;
    address: number;
    /** µg/√Hz; the BNO055's datasheet figure is 150. */
    noiseDensity_ug: number;
    /** Keep every sample the chip produced (ground truth for tests), or with a number about that many of the latest. */
    recordSamples?: boolean | number;
  };
  /** An RGB LED strip on the tool, driven by `device` on `pin`, photographed from above. */
  ledStrip?: { device: string; pin: number; strip: LedStripConfig; image: ExposureImageConfig };
  /** A pen on a servo, driven by `device`. */
  pen?: PenServoConfig & { device: string };
  /** Record the tool's true state every `period_us` (ground truth for tests and plots). */
  toolTrace?: { period_us: number };
}
