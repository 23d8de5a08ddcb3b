/** The tool's true state sampled at a fixed period: columns of a growable table. */
export class ToolTrace {
  readonly t_us: number[] = [];
  /** Per Cartesian axis: position mm, velocity mm/s, acceleration mm/s². */
  readonly position: Record<string, number[]> = {};
  readonly velocity: Record<string, number[]> = {};
  readonly acceleration: Record<string, number[]> = {};
  private next_us: number;

  constructor(
    readonly period_us: number,
    readonly axes: string[],
    start_us: number,
  ) {
    this.next_us = Math.ceil(start_us / period_us) * period_us;
    for (const a of axes) {
      this.position[a] = [];
      this.velocity[a] = [];
      this.acceleration[a] = [];
    }
  }

  /** Records every sample time in (…, t1_us]. */
  record(t1_us: number, stateAt: (axis: string, t_us: number) => { position: number; velocity: number; acceleration: number }): void {
    for (; this.next_us <= t1_us; this.next_us += this.period_us) {
      this.t_us.push(this.next_us);
      for (const a of this.axes) {
        const s = stateAt(a, this.next_us);
        this.position[a].push(s.position);
        this.velocity[a].push(s.velocity);
        this.acceleration[a].push(s.acceleration);
      }
    }
  }
}
