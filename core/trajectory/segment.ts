/**
 * One segment of the trajectory: geometry × timing (docs/design.md, decision 1).
 *
 * Geometry is a straight line from `start` to `end` in the motion axes, with unit
 * direction `unit` and `length` mm. Every position track is affine in the path
 * length s: motion axis i is start[i] + unit[i]·s, and actuator axis j is
 * actuatorStart[j] + actuatorRate[j]·s (exact for linear transforms; within the
 * stated tolerance for nonlinear ones, whose lines are subdivided first).
 *
 * A dwell (moves.ts) is a segment of length 0 with a zero direction: it holds
 * its start, and its timing is one phase at speed 0 lasting `dwell_s`.
 *
 * Timing is s(t) as polynomial phases (plan/phases.ts), set once the planner's
 * plan for the segment is final. Its absolute start time, in author µs, is set when
 * the segment is transmitted.
 */
import type { BlockLimits } from '../plan/lookahead.ts';
import { dwellTiming, timingDuration, trapezoidTiming, type Timing } from '../plan/phases.ts';
import type { EventTrack, ResolvedEventSpec } from './events.ts';
import type { ValidatedMove } from './validatedMove.ts';

const NO_ACTUATORS: number[] = [];

/** The paper's four states, in order. */
export type SegmentState = 'unplanned' | 'planned' | 'transmitted' | 'historical';

export class Segment implements BlockLimits {
  readonly id: number;
  /** The addSegmentToQueue call this segment came from; a nonlinear transform splits one move into many segments. */
  readonly moveId: number;
  /** That move, validated: an edit re-creates later segments from it. */
  readonly source: ValidatedMove;
  state: SegmentState = 'unplanned';

  // geometry
  readonly start: number[];
  readonly end: number[];
  readonly unit: number[];
  readonly length: number;
  /** mm along the move at which this segment starts (0 unless the move was subdivided). */
  readonly moveOffset: number;
  /** s that a dwell holds its position; null for a line. */
  readonly dwell_s: number | null;
  /** Each actuator axis at the segment's start, and its rate d(actuator)/ds. */
  actuatorStart: number[] = NO_ACTUATORS;
  actuatorRate: number[] = NO_ACTUATORS;
  /** Event channel values or evaluators for this segment, if any. */
  readonly events: readonly ResolvedEventSpec[];

  // planner: limits along this segment (BlockLimits, set by moves.ts) and the planned speeds²
  accel = 0;
  cruise2 = 0;
  maxEntry2 = 0;
  entry2 = 0;
  exit2 = 0;

  // timing
  /** s(t) as packed phases, final once the segment is planned. Null before. */
  timing: Timing | null = null;
  /** s, or NaN before the segment is timed. */
  duration_s = NaN;
  /** Author time, µs, at which the segment starts. NaN until it is transmitted. */
  startTime_us = NaN;

  // events
  /** The event tracks sampled from `events` for the current timing; null until built. */
  eventTracks: EventTrack[] | null = null;
  /** Every event channel's value as the segment begins; set when it is transmitted. */
  eventsAtStart: readonly number[] | null = null;

  constructor(
    id: number,
    moveId: number,
    start: number[],
    end: number[],
    unit: number[],
    length: number,
    moveOffset: number,
    source: ValidatedMove,
    dwell_s: number | null = null,
  ) {
    this.id = id;
    this.moveId = moveId;
    this.source = source;
    this.start = start;
    this.end = end;
    this.unit = unit;
    this.length = length;
    this.moveOffset = moveOffset;
    this.events = source.events;
    this.dwell_s = dwell_s;
  }

  /** Whether this segment is a dwell (length 0, at rest for dwell_s). */
  get isDwell(): boolean {
    return this.dwell_s !== null;
  }

  /** Builds the timing from the planner's entry and exit speeds (dropping event tracks built for older timing). */
  time(): Timing {
    const timing = this.dwell_s !== null ? dwellTiming(this.dwell_s) : trapezoidTiming(this.length, this.entry2, this.exit2, this.cruise2, this.accel);
    this.timing = timing;
    this.duration_s = timingDuration(timing);
    this.eventTracks = null;
    return timing;
  }

  /** Forgets the timing (an edit made the plan provisional again). */
  untime(): void {
    this.timing = null;
    this.duration_s = NaN;
    this.eventTracks = null;
  }

  get endTime_us(): number {
    return this.startTime_us + this.duration_s * 1e6;
  }

  get locked(): boolean {
    return this.state === 'transmitted' || this.state === 'historical';
  }
}
