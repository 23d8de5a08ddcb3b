/**
 * A stepper motor behind a step/dir driver. The driver moves the motor one
 * step on each rising edge of STEP, in the direction DIR holds at that moment
 * (high = positive, unless the motor is wired inverted). The motor position is
 * steps / stepsPerMm, from where it was at power-up.
 *
 * This is the plant's view: it counts what the pins did, independently of the
 * firmware's own step counter (which a session re-references without moving).
 */
export interface StepperMotorConfig {
  /** The motor's name in the plant (an actuator axis: "a", "b", "x"). */
  name: string;
  stepPin: number;
  dirPin: number;
  stepsPerMm: number;
  /** True if DIR low means positive. */
  invertDirection?: boolean;
  /** Position at power-up, mm. */
  initialPosition_mm?: number;
}

export class StepperMotor {
  private stepLevel = 0;
  private dirLevel = 0;
  /** Net steps since power-up. */
  steps = 0;
  stepsForward = 0;
  stepsBackward = 0;
  /** Author time of the latest step, µs. */
  lastStep_us = -Infinity;

  constructor(
    readonly config: StepperMotorConfig,
    /** Called after each step with the new position. */
    private readonly onStep: (position_mm: number, t_us: number) => void = () => {},
  ) {}

  get position_mm(): number {
    return (this.config.initialPosition_mm ?? 0) + this.steps / this.config.stepsPerMm;
  }

  /** A digital write on one of this motor's pins. Returns false if the pin is not one of them. */
  pinWrite(pin: number, level: number, t_us: number): boolean {
    const high = level !== 0 ? 1 : 0;
    if (pin === this.config.dirPin) {
      this.dirLevel = high;
      return true;
    }
    if (pin !== this.config.stepPin) return false;
    const rising = high === 1 && this.stepLevel === 0;
    this.stepLevel = high;
    if (rising) {
      const positive = (this.dirLevel === 1) !== (this.config.invertDirection ?? false);
      this.steps += positive ? 1 : -1;
      if (positive) this.stepsForward++;
      else this.stepsBackward++;
      this.lastStep_us = t_us;
      this.onStep(this.position_mm, t_us);
    }
    return true;
  }
}
