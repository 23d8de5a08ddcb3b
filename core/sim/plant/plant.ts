/**
 * The simulated machine's physical side, driven by the firmware's outputs:
 *
 *   step/dir pins ─▶ StepperMotor ─▶ kinematics (CoreXY inverse) ─▶ carriage
 *   carriage ─▶ SpringAxis (belt spring, per Cartesian axis) ─▶ tool
 *   tool ─▶ Bno055 (I2C), LedExposure (long exposure), PenServo (drawing)
 *
 * Time only moves forward: every input comes with its author time, and the
 * device runner delivers them in time order across devices. Before applying
 * an input at t, the plant advances to t: the spring axes run their closed
 * form, and the time-integrated instruments (exposure, pen, trace) integrate
 * over the interval, during which the carriage was still.
 *
 * Ground truth for tests: motor steps and positions, the tool's state at any
 * recent time, the exposure image, pen strokes, accelerometer samples.
 */
import type { DeviceHardware } from '../device/deviceHardware.ts';
import { deriveSeed, seededRandom } from '../../random.ts';
import { Bno055 } from './bno055.ts';
import { carriagePositions, cartesianAxes } from './kinematics.ts';
import { LedExposure } from './ledExposure.ts';
import { PenServo } from './penServo.ts';
import type { PlantConfig } from './plantConfig.ts';
import { SpringAxis, type ToolAxisState } from './springAxis.ts';
import type { SpringParameters } from './springResponse.ts';
import { StepperMotor } from './stepperMotor.ts';
import { ToolTrace } from './toolTrace.ts';

const STANDARD_GRAVITY = 9.80665;

export class Plant {
  readonly motors: Record<string, StepperMotor> = {};
  /** Tool dynamics per Cartesian axis ("x", "y"). */
  readonly axes: Record<string, SpringAxis> = {};
  readonly axisNames: string[];
  readonly accelerometer: Bno055 | null = null;
  readonly leds: LedExposure | null = null;
  readonly pen: PenServo | null = null;
  readonly trace: ToolTrace | null = null;
  /** Last level written to each device's pins, for digitalRead of outputs. */
  private readonly pinLevels = new Map<string, Map<number, number>>();
  private t_us: number;

  constructor(
    readonly config: PlantConfig,
    options: { seed: number; start_us?: number },
  ) {
    this.t_us = options.start_us ?? 0;
    for (const m of config.motors) {
      if (this.motors[m.name]) throw new RangeError(`plant: motor "${m.name}" is declared twice`);
      this.motors[m.name] = new StepperMotor(m, (_position, t) => this.onMotorStep(t));
    }
    this.axisNames = cartesianAxes(config.kinematics);
    const carriage = carriagePositions(config.kinematics, this.motorPositions());
    for (const axis of this.axisNames) this.axes[axis] = new SpringAxis(this.springFor(axis), this.t_us, carriage[axis]);
    if (config.accelerometer) {
      const a = config.accelerometer;
      this.accelerometer = new Bno055(
        { address: a.address, noiseDensity_ug: a.noiseDensity_ug },
        (t, w) => this.specificForce(t, w),
        seededRandom(deriveSeed(options.seed, `accelerometer/${a.device}`)),
        { recordSamples: a.recordSamples },
      );
    }
    if (config.ledStrip) this.leds = new LedExposure(config.ledStrip.strip, config.ledStrip.image);
    if (config.pen) this.pen = new PenServo(config.pen);
    if (config.toolTrace) this.trace = new ToolTrace(config.toolTrace.period_us, this.axisNames, this.t_us);
  }

  get time_us(): number {
    return this.t_us;
  }

  /** Runs the plant to author time `t_us` with no new input (earlier times are ignored). */
  advanceTo(t_us: number): void {
    if (t_us <= this.t_us) return;
    const t0 = this.t_us;
    const toolXY = (t: number) => this.toolXY(t);
    this.pen?.advance(t0, t_us, toolXY);
    this.leds?.expose(t0, t_us, toolXY);
    this.trace?.record(t_us, (axis, t) => this.axes[axis].stateAt(t));
    for (const axis of this.axisNames) this.axes[axis].advanceTo(t_us);
    this.t_us = t_us;
  }

  // ---- ground truth

  motorPositions(): Record<string, number> {
    const out: Record<string, number> = {};
    for (const [name, m] of Object.entries(this.motors)) out[name] = m.position_mm;
    return out;
  }

  motorSteps(): Record<string, number> {
    const out: Record<string, number> = {};
    for (const [name, m] of Object.entries(this.motors)) out[name] = m.steps;
    return out;
  }

  /** Carriage position per Cartesian axis (motor side of the belt), mm. */
  carriage(): Record<string, number> {
    return carriagePositions(this.config.kinematics, this.motorPositions());
  }

  /** The tool's true state per axis at `t_us` (default: the plant's time); any time since the recent history kept. */
  tool(t_us: number = this.t_us): Record<string, ToolAxisState> {
    const out: Record<string, ToolAxisState> = {};
    for (const axis of this.axisNames) out[axis] = this.axes[axis].stateAt(t_us);
    return out;
  }

  /** The tool's position in the plane (first two Cartesian axes; 0 for a missing one), mm. */
  toolXY(t_us: number = this.t_us): [number, number] {
    const [ax, ay] = this.axisNames;
    return [ax ? this.axes[ax].stateAt(t_us).position : 0, ay ? this.axes[ay].stateAt(t_us).position : 0];
  }

  // ---- the devices' side

  /** The pins and buses of device `device`, wired to this plant. */
  hardwareFor(device: string): DeviceHardware {
    const motors = this.config.motors.filter((m) => m.device === device).map((m) => this.motors[m.name]);
    const levels = new Map<number, number>();
    this.pinLevels.set(device, levels);
    const acc = this.config.accelerometer?.device === device ? this.accelerometer : null;
    const strip = this.config.ledStrip?.device === device ? this.config.ledStrip : null;
    const pen = this.config.pen?.device === device ? this.pen : null;
    return {
      pinMode: () => {},
      digitalWrite: (pin, value, t) => {
        this.advanceTo(t);
        levels.set(pin, value ? 1 : 0);
        for (const m of motors) if (m.pinWrite(pin, value, t)) break;
      },
      digitalRead: (pin) => levels.get(pin) ?? 0,
      analogWrite: (pin, value, t) => {
        this.advanceTo(t);
        levels.set(pin, value > 127 ? 1 : 0);
      },
      ledShow: (pin, rgb, t) => {
        this.advanceTo(t);
        if (strip && pin === strip.pin) this.leds?.show(rgb);
      },
      i2cWrite: (address, data, t) => {
        this.advanceTo(t);
        return acc ? acc.i2cWrite(address, data) : 2;
      },
      i2cRead: (address, length, t) => {
        this.advanceTo(t);
        return acc ? acc.i2cRead(address, length, t) : null;
      },
      servoPulse: (pin, pulse, t) => {
        this.advanceTo(t);
        if (pen && pin === pen.config.pin) pen.pulse(pulse, t);
      },
    };
  }

  private onMotorStep(t_us: number): void {
    const carriage = carriagePositions(this.config.kinematics, this.motorPositions());
    for (const axis of this.axisNames) this.axes[axis].setCarriage(carriage[axis], t_us);
  }

  private springFor(axis: string): SpringParameters {
    const s = this.config.spring;
    if ('naturalFrequency_hz' in s) return s as SpringParameters;
    const p = (s as Record<string, SpringParameters>)[axis];
    if (!p) throw new RangeError(`plant: no spring parameters for axis "${axis}"`);
    return p;
  }

  /**
   * What an accelerometer on the tool measures, m/s², machine frame, averaged
   * over [t − w, t]: the mean acceleration (v(t) − v(t − w))/w per axis, and
   * +1 g on z (specific force: at rest the sensor reads gravity's reaction).
   */
  private specificForce(t_us: number, window_us: number): [number, number, number] {
    const [ax, ay] = this.axisNames;
    const mean = (axis: string | undefined) =>
      axis ? ((this.axes[axis].stateAt(t_us).velocity - this.axes[axis].stateAt(t_us - window_us).velocity) / (window_us * 1e-6)) * 1e-3 : 0;
    return [mean(ax), mean(ay), STANDARD_GRAVITY];
  }
}
