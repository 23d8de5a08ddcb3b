/**
 * A line's planner inputs from the machine's limits, with what does not depend on
 * the line's direction worked out once per machine rather than once per line: a
 * queue or planPath computes them for a million lines a second.
 *
 * Each method returns exactly what its counterpart in moves.ts returns (lineCruise2,
 * lineAccel, entryCap2 at a corner), to the bit: when no axis has a limit of its
 * own, projectLimit() (config/limits.ts) returns the magnitude unchanged, so
 * skipping it changes nothing; otherwise the same function runs.
 */
import { boundsAnAxis, projectLimit, type ResolvedLimits } from '../config/limits.ts';
import { cornerSpeed2 } from '../plan/junction.ts';

export class LineLimits {
  readonly limits: ResolvedLimits;
  private readonly speedPerAxis: boolean;
  private readonly accelPerAxis: boolean;

  constructor(limits: ResolvedLimits) {
    this.limits = limits;
    this.speedPerAxis = boundsAnAxis(limits.axisMaxSpeed);
    this.accelPerAxis = boundsAnAxis(limits.axisMaxAccel);
  }

  /** The speed² cap (mm²/s²) of a line along `unit` with the move's own cap `maxVelocity` (moves.ts lineCruise2). */
  cruise2(maxVelocity: number, unit: readonly number[]): number {
    const l = this.limits;
    const machine = this.speedPerAxis ? projectLimit(l.maxSpeed, l.axisMaxSpeed, unit) : l.maxSpeed;
    const speed = Math.min(maxVelocity, machine);
    return speed * speed;
  }

  /** The acceleration limit (mm/s²) of a line along `unit` with the move's own cap (moves.ts lineAccel). */
  accel(maxAcceleration: number, unit: readonly number[]): number {
    const l = this.limits;
    return Math.min(maxAcceleration, this.accelPerAxis ? projectLimit(l.maxAccel, l.axisMaxAccel, unit) : l.maxAccel);
  }

  /** The entry cap (mm²/s²) of a line after a corner with the tail (moves.ts entryCap2 with `corner`). */
  entryCap2(prevUnit: readonly number[] | null, prevCruise2: number, unit: readonly number[], cruise2: number): number {
    if (prevUnit === null) return 0;
    return Math.min(cornerSpeed2(prevUnit, unit, this.limits, this.accelPerAxis), cruise2, prevCruise2);
  }
}
