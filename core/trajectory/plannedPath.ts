/**
 * The result of planPath, kept in columns (one typed array per quantity, a row per
 * segment) rather than as an object per segment: planning a 100 000-segment path
 * then allocates a dozen arrays, not a million objects. `duration` and `sample(t)`
 * read the columns directly; `segments` builds the familiar objects on first use
 * (and keeps them), for code that iterates the plan.
 *
 * Rows: segment i runs from vertex i to vertex i + 1 (a dwell's two vertices are the
 * same point), starts at startTime(i) s and lasts durations[i] s. Its phases are
 * not stored (18 numbers a row): they are made again from the row's length, speeds²
 * and limits, by the functions the queue's segments use, when a sample or a segment
 * object needs them.
 */
import { MaxlError } from '../errors.ts';
import { dwellTiming, phasesOf, trapezoidTiming, type Phase, type Timing } from '../plan/phases.ts';
import { sampleTimeline, type TimedSegment, type TrajectorySample } from './tracks.ts';

export interface PlannedSegment {
  start: number[];
  end: number[];
  /** mm */
  length: number;
  /** s since the path began */
  startTime: number;
  /** s */
  duration: number;
  /** mm/s */
  entryVelocity: number;
  exitVelocity: number;
  /** mm/s, the highest speed reached inside the segment */
  peakVelocity: number;
  /** mm/s, the cap the planner had for this segment (limits, the move's maxVelocity, the link's floor; 0 for a dwell) */
  cruiseLimit: number;
  /** mm/s², the acceleration limit along the segment (0 for a dwell, which has no direction) */
  accelerationLimit: number;
  /** Whether this is a dwell: start = end, length 0, speed 0 throughout, lasting `duration`. */
  dwell: boolean;
  phases: Phase[];
}

export interface PathSample {
  position: number[];
  velocity: number[];
  acceleration: number[];
}

export interface PlannedPath {
  /** s */
  duration: number;
  /** Segments planned (moves less the zero-length ones skipped). */
  segmentCount: number;
  /** The planned segments as objects, built on first use. */
  segments: PlannedSegment[];
  /** Zero-length moves skipped. */
  skipped: number;
  /** The state at t seconds after the start (clamped: at rest before 0 and after `duration`). */
  sample(t: number): PathSample;
}

/** The columns planPath fills, one row per segment. */
export class PathColumns {
  readonly axes: number;
  count = 0;
  /** (count + 1) × axes, mm */
  vertices: Float64Array;
  lengths: Float64Array;
  /** (mm/s)² */
  cruise2s: Float64Array;
  accels: Float64Array;
  entry2s: Float64Array;
  exit2s: Float64Array;
  dwells: Uint8Array;
  /** s; a dwell's is its own dwell_s */
  durations: Float64Array;
  /** s since the path began, made from the durations on first use (startTime): planning needs only their sum. */
  private startTimes: Float64Array | null = null;

  constructor(axes: number, capacity: number, start: readonly number[]) {
    this.axes = axes;
    const n = Math.max(1, capacity);
    this.vertices = new Float64Array((n + 1) * axes);
    for (let a = 0; a < axes; a++) this.vertices[a] = start[a];
    this.lengths = new Float64Array(n);
    this.cruise2s = new Float64Array(n);
    this.accels = new Float64Array(n);
    this.entry2s = new Float64Array(n);
    this.exit2s = new Float64Array(n);
    this.dwells = new Uint8Array(n);
    this.durations = new Float64Array(n);
  }

  /** s, when row i starts: the durations before it summed in path order (as planPath sums the total). */
  startTime(i: number): number {
    if (this.startTimes === null) {
      const starts = new Float64Array(Math.max(1, this.count));
      let t = 0;
      for (let k = 0; k < this.count; k++) {
        starts[k] = t;
        t += this.durations[k];
      }
      this.startTimes = starts;
    }
    return this.startTimes[i];
  }

  /** Row i's timing, as Segment.time() makes it. */
  timingOf(i: number): Timing {
    return this.dwells[i] === 1
      ? dwellTiming(this.durations[i])
      : trapezoidTiming(this.lengths[i], this.entry2s[i], this.exit2s[i], this.cruise2s[i], this.accels[i]);
  }

  vertex(i: number): number[] {
    return Array.from(this.vertices.subarray(i * this.axes, (i + 1) * this.axes));
  }
}

export class ColumnarPlannedPath implements PlannedPath {
  readonly duration: number;
  readonly skipped: number;
  private readonly columns: PathColumns;
  private built: PlannedSegment[] | null = null;

  constructor(columns: PathColumns, duration: number, skipped: number) {
    this.columns = columns;
    this.duration = duration;
    this.skipped = skipped;
  }

  get segmentCount(): number {
    return this.columns.count;
  }

  get segments(): PlannedSegment[] {
    if (this.built === null) {
      const built = new Array<PlannedSegment>(this.columns.count);
      for (let i = 0; i < built.length; i++) built[i] = this.segment(i);
      this.built = built;
    }
    return this.built;
  }

  /** Segment i as an object (a new one each call). */
  segment(i: number): PlannedSegment {
    const c = this.columns;
    const phases: Phase[] = phasesOf(c.timingOf(i));
    let peak = 0;
    // Constant acceleration in each phase: the highest speed is at one of its ends.
    for (const phase of phases) peak = Math.max(peak, phase.v0, phase.v0 + phase.a0 * phase.duration);
    const dwell = c.dwells[i] === 1;
    return {
      start: c.vertex(i),
      end: c.vertex(i + 1),
      length: c.lengths[i],
      startTime: c.startTime(i),
      duration: c.durations[i],
      entryVelocity: Math.sqrt(c.entry2s[i]),
      exitVelocity: Math.sqrt(c.exit2s[i]),
      peakVelocity: peak,
      cruiseLimit: Math.sqrt(c.cruise2s[i]),
      accelerationLimit: dwell ? 0 : c.accels[i],
      dwell,
      phases,
    };
  }

  sample(time: number): PathSample {
    if (typeof time !== 'number' || Number.isNaN(time)) throw new MaxlError('MOVE_INVALID', `must be a time in s, got ${String(time)}`, 't');
    const c = this.columns;
    const s: TrajectorySample | null = sampleTimeline(0, c.count, (i) => this.timedSegment(i), (i) => c.startTime(i), time, 1);
    if (s === null) {
      const start = c.vertex(0);
      return { position: start, velocity: start.map(() => 0), acceleration: start.map(() => 0) };
    }
    return { position: s.position, velocity: s.velocity, acceleration: s.acceleration };
  }

  /** Row i as tracks.ts samples it: the unit direction is (end − start)/length, as moves.ts makes it (zero for a dwell). */
  private timedSegment(i: number): TimedSegment {
    const c = this.columns;
    const start = c.vertex(i);
    const end = c.vertex(i + 1);
    const length = c.lengths[i];
    const unit = start.map((p, a) => (length > 0 ? (end[a] - p) / length : 0));
    return { start, end, unit, actuatorStart: [], actuatorRate: [], timing: c.timingOf(i) };
  }
}
