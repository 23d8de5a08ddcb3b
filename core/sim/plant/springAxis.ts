/**
 * One axis of the tool on its belt spring (springResponse.ts), driven by the
 * carriage position u, which changes in steps at the times the motors step.
 *
 * The axis keeps its state at the latest input time, and a ring of recent
 * checkpoints (the state just after each input change) so that its exact state
 * at any recent past time can be recomputed: an accelerometer averaging over
 * its last sample period needs the velocity a millisecond ago.
 */
import { springAcceleration, springAfter, type SpringParameters, type SpringState } from './springResponse.ts';

export interface ToolAxisState {
  /** mm */
  position: number;
  /** mm/s */
  velocity: number;
  /** mm/s² */
  acceleration: number;
  /** The carriage (motor side) position, mm. */
  carriage: number;
}

export class SpringAxis {
  private t_us: number;
  private u: number;
  private state: SpringState;
  private readonly ringT: Float64Array;
  private readonly ringX: Float64Array;
  private readonly ringV: Float64Array;
  private readonly ringU: Float64Array;
  private ringNext = 0;
  private ringCount = 0;
  private readonly start_us: number;
  private readonly startPosition: number;

  constructor(
    readonly params: SpringParameters,
    start_us: number,
    /** Carriage and tool start at rest here, mm. */
    position: number,
    historyCapacity = 16384,
  ) {
    this.t_us = start_us;
    this.start_us = start_us;
    this.startPosition = position;
    this.u = position;
    this.state = { x: position, v: 0 };
    this.ringT = new Float64Array(historyCapacity);
    this.ringX = new Float64Array(historyCapacity);
    this.ringV = new Float64Array(historyCapacity);
    this.ringU = new Float64Array(historyCapacity);
    this.checkpoint();
  }

  get time_us(): number {
    return this.t_us;
  }

  get carriage(): number {
    return this.u;
  }

  /** Moves the axis's clock to `t_us` (not before its current time) with the carriage held. */
  advanceTo(t_us: number): void {
    if (t_us <= this.t_us) return;
    this.state = springAfter(this.state, this.u, (t_us - this.t_us) * 1e-6, this.params);
    this.t_us = t_us;
  }

  /** The carriage moves to `u` (mm) at `t_us`. */
  setCarriage(u: number, t_us: number): void {
    this.advanceTo(t_us);
    if (u === this.u) return;
    this.u = u;
    this.checkpoint();
  }

  /**
   * The tool's state at `t_us`: exact for any time since the oldest checkpoint
   * kept; for times after the axis's clock it assumes the carriage stays put.
   * Before the axis was made, the tool was at rest where it started.
   */
  stateAt(t_us: number): ToolAxisState {
    if (t_us < this.start_us) return { position: this.startPosition, velocity: 0, acceleration: 0, carriage: this.startPosition };
    let base: SpringState;
    let baseT: number;
    let u: number;
    if (t_us >= this.t_us) {
      base = this.state;
      baseT = this.t_us;
      u = this.u;
    } else {
      const k = this.checkpointBefore(t_us);
      base = { x: this.ringX[k], v: this.ringV[k] };
      baseT = this.ringT[k];
      u = this.ringU[k];
    }
    const s = springAfter(base, u, (t_us - baseT) * 1e-6, this.params);
    return { position: s.x, velocity: s.v, acceleration: springAcceleration(s, u, this.params), carriage: u };
  }

  private checkpoint(): void {
    const k = this.ringNext;
    this.ringT[k] = this.t_us;
    this.ringX[k] = this.state.x;
    this.ringV[k] = this.state.v;
    this.ringU[k] = this.u;
    this.ringNext = (k + 1) % this.ringT.length;
    this.ringCount = Math.min(this.ringCount + 1, this.ringT.length);
  }

  /** Ring index of the latest checkpoint at or before `t_us` (binary search over the ring in time order). */
  private checkpointBefore(t_us: number): number {
    const n = this.ringCount;
    const cap = this.ringT.length;
    const oldest = (this.ringNext - n + cap) % cap;
    const at = (i: number) => (oldest + i) % cap;
    if (t_us < this.ringT[at(0)]) {
      throw new RangeError(`tool state at ${t_us} µs is older than the ${n} checkpoints kept (oldest ${this.ringT[at(0)]} µs)`);
    }
    let lo = 0;
    let hi = n - 1;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (this.ringT[at(mid)] <= t_us) lo = mid;
      else hi = mid - 1;
    }
    return at(lo);
  }
}
