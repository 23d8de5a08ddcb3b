/**
 * One segment of the trajectory: geometry × timing (DESIGN.md decision 1).
 *
 * Geometry is a straight line from `start` to `end` in the motion axes, with unit
 * direction `unit` and `length` mm. Every position track is affine in the path
 * length s: motion axis i is start[i] + unit[i]·s, and actuator axis j is
 * actuatorStart[j] + actuatorRate[j]·s (exact for linear transforms; within the
 * stated tolerance for nonlinear ones, whose lines are subdivided first).
 *
 * Timing is s(t) as polynomial phases (plan/phases.ts), set once the planner's
 * plan for the segment is final. Its absolute start time, in author µs, is set when
 * the segment is transmitted.
 */
import type { PlanBlock } from '../plan/lookahead.ts';
import { phasesDuration, trapezoidPhases, type Phase } from '../plan/phases.ts';
import type { ResolvedEventSpec } from './events.ts';

/** The paper's four states, in order. */
export type SegmentState = 'unplanned' | 'planned' | 'transmitted' | 'historical';

export class Segment implements PlanBlock {
  readonly id: number;
  /** The addSegmentToQueue call this segment came from; a nonlinear transform splits one move into many segments. */
  readonly moveId: number;
  state: SegmentState = 'unplanned';

  // geometry
  readonly start: number[];
  readonly end: number[];
  readonly unit: number[];
  readonly length: number;
  /** mm along the move at which this segment starts (0 unless the move was subdivided). */
  readonly moveOffset: number;
  readonly actuatorStart: number[];
  readonly actuatorRate: number[];
  /** Event channel values or evaluators for this segment, if any. */
  readonly events: readonly ResolvedEventSpec[];

  // planner (PlanBlock)
  accel: number;
  cruise2: number;
  maxEntry2: number;
  entry2 = 0;
  exit2 = 0;
  work = 0;

  // timing
  /** s(t), final once the segment is planned. Null before. */
  phases: Phase[] | null = null;
  /** Author time, µs, at which the segment starts. NaN until it is transmitted. */
  startTime_us = NaN;

  constructor(init: {
    id: number;
    moveId: number;
    start: number[];
    end: number[];
    unit: number[];
    length: number;
    moveOffset: number;
    actuatorStart: number[];
    actuatorRate: number[];
    events: readonly ResolvedEventSpec[];
    accel: number;
    cruise2: number;
    maxEntry2: number;
  }) {
    this.id = init.id;
    this.moveId = init.moveId;
    this.start = init.start;
    this.end = init.end;
    this.unit = init.unit;
    this.length = init.length;
    this.moveOffset = init.moveOffset;
    this.actuatorStart = init.actuatorStart;
    this.actuatorRate = init.actuatorRate;
    this.events = init.events;
    this.accel = init.accel;
    this.cruise2 = init.cruise2;
    this.maxEntry2 = init.maxEntry2;
  }

  /** Builds the phases from the planner's entry and exit speeds. */
  time(): Phase[] {
    this.phases = trapezoidPhases(this.length, this.entry2, this.exit2, this.cruise2, this.accel);
    return this.phases;
  }

  /** s, or NaN before the segment is timed. */
  get duration_s(): number {
    return this.phases ? phasesDuration(this.phases) : NaN;
  }

  get endTime_us(): number {
    return this.startTime_us + this.duration_s * 1e6;
  }

  get locked(): boolean {
    return this.state === 'transmitted' || this.state === 'historical';
  }
}
