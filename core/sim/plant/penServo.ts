/**
 * A pen on a hobby servo. The firmware sets a pulse width; the pen is
 * commanded down when the pulse is nearer `downPulse_us` than `upPulse_us`.
 * The servo takes time to swing: the pen touches the paper `dropDelay_us`
 * after a down command, and leaves it `liftDelay_us` after an up command. A
 * command that reverses a swing still in progress cancels it (the pen had not
 * reached the other state yet), so the pen state is a clean step function of
 * time: `transitions`.
 *
 * While the pen is down, the plant samples the tool path into strokes (the
 * drawing). A pulse of 0 detaches the servo: the pen stays where it is.
 */
export interface PenServoConfig {
  pin: number;
  upPulse_us: number;
  downPulse_us: number;
  dropDelay_us: number;
  liftDelay_us: number;
  /** Pen-down path sampling period, µs. */
  tracePeriod_us: number;
  /** A sample closer than this to the stroke's previous point is skipped, mm (so a resting pen adds nothing). */
  traceMinDistance_mm: number;
}

export interface PenTransition {
  /** Author time the pen reached its new state, µs. */
  t_us: number;
  down: boolean;
}

export interface PenStroke {
  /** Author time of each point, µs, and the tool position there, mm. */
  t_us: number[];
  x: number[];
  y: number[];
}

export class PenServo {
  readonly transitions: PenTransition[] = [];
  readonly strokes: PenStroke[] = [];
  /** Pulses received, with their author times. */
  readonly pulses: Array<{ t_us: number; pulse_us: number }> = [];
  private down = false;
  private commandedDown = false;
  /** A swing in progress: when it lands and where. */
  private pending: PenTransition | null = null;
  private lastSample_us = -Infinity;

  constructor(readonly config: PenServoConfig) {}

  /** Whether the pen touches the paper now (after `advanceTo`). */
  get isDown(): boolean {
    return this.down;
  }

  /** The pen's state at author time t, from its recorded transitions (for times already simulated). */
  isDownAt(t_us: number): boolean {
    let state = false;
    for (const tr of this.transitions) {
      if (tr.t_us > t_us) break;
      state = tr.down;
    }
    return state;
  }

  /** A new pulse width from the firmware at `t_us`. Call after advancing the plant to `t_us`. */
  pulse(pulse_us: number, t_us: number): void {
    this.pulses.push({ t_us, pulse_us });
    if (pulse_us === 0) return;
    const wantDown = Math.abs(pulse_us - this.config.downPulse_us) < Math.abs(pulse_us - this.config.upPulse_us);
    if (wantDown === this.commandedDown) return;
    this.commandedDown = wantDown;
    if (wantDown === this.down) {
      this.pending = null; // reversed before landing
      return;
    }
    this.pending = { t_us: t_us + (wantDown ? this.config.dropDelay_us : this.config.liftDelay_us), down: wantDown };
  }

  /** When the next swing lands, or Infinity. */
  get nextTransition_us(): number {
    return this.pending ? this.pending.t_us : Infinity;
  }

  /**
   * Runs the pen from its last time to t1 (the plant calls this in order, with
   * the tool's position available at any time in between): lands a pending
   * swing if due, and samples the path while down.
   */
  advance(t0_us: number, t1_us: number, toolAt: (t_us: number) => [number, number]): void {
    let t = t0_us;
    while (this.pending && this.pending.t_us <= t1_us) {
      if (this.pending.t_us < t) throw new RangeError(`pen advanced out of order: swing due at ${this.pending.t_us} µs, already at ${t} µs`);
      this.sample(this.pending.t_us, toolAt);
      t = this.pending.t_us;
      this.down = this.pending.down;
      this.transitions.push(this.pending);
      this.pending = null;
      if (this.down) {
        this.strokes.push({ t_us: [], x: [], y: [] });
        this.lastSample_us = -Infinity;
        this.addPoint(t, toolAt);
      } else {
        this.addPointTo(this.strokes[this.strokes.length - 1], t, toolAt);
      }
    }
    this.sample(t1_us, toolAt);
  }

  /**
   * Samples the path every tracePeriod_us while the pen is down, from the
   * stroke's start, up to t1 (calls come in time order).
   */
  private sample(t1_us: number, toolAt: (t_us: number) => [number, number]): void {
    if (!this.down) return;
    const period = this.config.tracePeriod_us;
    const stroke = this.strokes[this.strokes.length - 1];
    for (let t = this.lastSample_us + period; t <= t1_us; t += period) {
      this.lastSample_us = t;
      const [x, y] = toolAt(t);
      const n = stroke.x.length - 1;
      if (Math.hypot(x - stroke.x[n], y - stroke.y[n]) < this.config.traceMinDistance_mm) continue;
      stroke.t_us.push(t);
      stroke.x.push(x);
      stroke.y.push(y);
    }
  }

  private addPoint(t_us: number, toolAt: (t_us: number) => [number, number]): void {
    this.addPointTo(this.strokes[this.strokes.length - 1], t_us, toolAt);
    this.lastSample_us = t_us;
  }

  private addPointTo(stroke: PenStroke, t_us: number, toolAt: (t_us: number) => [number, number]): void {
    const [x, y] = toolAt(t_us);
    stroke.t_us.push(t_us);
    stroke.x.push(x);
    stroke.y.push(y);
  }
}
