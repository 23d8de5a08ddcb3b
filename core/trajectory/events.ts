/**
 * Event channels: time-stamped step functions that switch a laser, LEDs, a pen or
 * a sensor in step with the motion.
 *
 * A move sets a channel either to a fixed value for the whole segment, or with an
 * evaluator: a function of the machine's state, sampled every
 * `evaluationPrecision` ms once the segment's timing is final (paper, Listing 5).
 * Only changes are kept. Each segment's track is self-contained: it always holds
 * the value at the segment's start, then every change within it. A channel a move
 * does not mention keeps its last value.
 */
import { MaxlError } from '../errors.ts';
import { evaluateTiming, timingDuration, type PathState, type Timing } from '../plan/phases.ts';

/** What an evaluator sees: the full state of the machine at one instant of the segment. */
export interface EvaluatorState {
  /** s since this segment began */
  time: number;
  /** s, the segment's duration */
  duration: number;
  /** mm along this segment */
  distance: number;
  /** mm along the whole move (differs from distance when a nonlinear transform subdivided the move) */
  moveDistance: number;
  /** mm, every motion axis and actuator axis by name */
  position: Record<string, number>;
  /** mm/s per motion axis */
  velocity: number[];
  /** mm/s² per motion axis */
  acceleration: number[];
  /** mm/s along the path */
  speed: number;
  /** the segment's unit direction, per motion axis */
  unit: number[];
}

export interface EventEvaluatorSpec {
  name: string;
  /** ms between samples */
  evaluationPrecision: number;
  evaluator: (state: EvaluatorState) => number;
}

export interface EventValueSpec {
  name: string;
  value: number;
}

/** `{ powerOut: 0.8 }`, or a list of fixed values and evaluators. */
export type MoveEvents = Record<string, number> | Array<EventEvaluatorSpec | EventValueSpec>;

export interface ResolvedEventSpec {
  channel: number;
  value?: number;
  evaluator?: (state: EvaluatorState) => number;
  /** s */
  precision?: number;
}

/** One channel's changes within one segment: times in s since the segment began. */
export interface EventTrack {
  channel: number;
  times: number[];
  values: number[];
}

/**
 * Event values travel as 32-bit floats (docs/protocol.md §4 EVENTS): a double past
 * ±3.4·10³⁸ is finite here but infinite there.
 */
export function fitsWireFloat(value: unknown): value is number {
  return typeof value === 'number' && Number.isFinite(Math.fround(value));
}

function finiteValue(field: string, value: unknown): number {
  if (!fitsWireFloat(value)) {
    throw new MaxlError('MOVE_INVALID', `must be a finite number within ±3.4e38 (a 32-bit float on the wire), got ${String(value)}`, field);
  }
  return value;
}

/** What resolveMoveEvents gives a move that sets no event: one shared empty array. */
export const NO_SPECS: ResolvedEventSpec[] = [];

export function resolveMoveEvents(events: MoveEvents | undefined, channels: readonly string[]): ResolvedEventSpec[] {
  if (events === undefined) return NO_SPECS;
  const seen = new Set<number>();
  const channelOf = (field: string, name: unknown): number => {
    const index = typeof name === 'string' ? channels.indexOf(name) : -1;
    if (index < 0) {
      throw new MaxlError(
        'MOVE_INVALID',
        `"${String(name)}" is not an event channel (channels: ${channels.length ? channels.join(', ') : 'none configured'})`,
        field,
      );
    }
    if (seen.has(index)) throw new MaxlError('MOVE_INVALID', `channel "${name as string}" is set twice`, field);
    seen.add(index);
    return index;
  };
  if (Array.isArray(events)) {
    return events.map((spec, i) => {
      const field = `eventChannels[${i}]`;
      if (spec === null || typeof spec !== 'object') throw new MaxlError('MOVE_INVALID', 'must be an object', field);
      const channel = channelOf(`${field}.name`, spec.name);
      if ('evaluator' in spec) {
        if (typeof spec.evaluator !== 'function') throw new MaxlError('MOVE_INVALID', 'must be a function', `${field}.evaluator`);
        const ms = finiteValue(`${field}.evaluationPrecision`, spec.evaluationPrecision);
        if (ms <= 0) throw new MaxlError('MOVE_INVALID', 'must be a positive number of milliseconds', `${field}.evaluationPrecision`);
        return { channel, evaluator: spec.evaluator, precision: ms / 1000 };
      }
      return { channel, value: finiteValue(`${field}.value`, (spec as EventValueSpec).value) };
    });
  }
  if (typeof events !== 'object' || events === null) {
    throw new MaxlError('MOVE_INVALID', 'must be an object of channel values or a list of evaluators', 'eventChannels');
  }
  return Object.entries(events).map(([name, value]) => ({
    channel: channelOf(`eventChannels.${name}`, name),
    value: finiteValue(`eventChannels.${name}`, value),
  }));
}

/** What buildEventTracks needs to know of a timed segment. */
export interface TimedGeometry {
  timing: Timing;
  length: number;
  moveOffset: number;
  start: readonly number[];
  unit: readonly number[];
  actuatorStart: readonly number[];
  actuatorRate: readonly number[];
}

/**
 * Samples every event spec of a timed segment. An evaluator that throws or returns
 * a non-finite number raises a MOVE_INVALID error naming the channel and time.
 */
export function buildEventTracks(
  specs: readonly ResolvedEventSpec[],
  seg: TimedGeometry,
  motionAxes: readonly string[],
  actuatorAxes: readonly string[],
  channels: readonly string[],
): EventTrack[] {
  if (specs.length === 0) return [];
  const duration = timingDuration(seg.timing);
  const path: PathState = { s: 0, v: 0, a: 0 };
  return specs.map((spec) => {
    if (spec.evaluator === undefined) return { channel: spec.channel, times: [0], values: [spec.value as number] };
    const times: number[] = [];
    const values: number[] = [];
    const step = spec.precision as number;
    // Sample at 0, p, 2p, … up to (not at) the end: the next segment owns its start.
    const samples = Math.max(1, Math.ceil(duration / step - 1e-9));
    for (let k = 0; k < samples; k++) {
      const t = k * step;
      evaluateTiming(seg.timing, t, path);
      const position: Record<string, number> = {};
      motionAxes.forEach((name, i) => (position[name] = seg.start[i] + seg.unit[i] * path.s));
      actuatorAxes.forEach((name, i) => (position[name] = seg.actuatorStart[i] + seg.actuatorRate[i] * path.s));
      let value: number;
      try {
        value = spec.evaluator({
          time: t,
          duration,
          distance: path.s,
          moveDistance: seg.moveOffset + path.s,
          position,
          velocity: seg.unit.map((u) => u * path.v),
          acceleration: seg.unit.map((u) => u * path.a),
          speed: path.v,
          unit: [...seg.unit],
        });
      } catch (err) {
        throw new MaxlError('MOVE_INVALID', `evaluator threw at t = ${t.toFixed(4)} s: ${err instanceof Error ? err.message : String(err)}`, `eventChannels.${channels[spec.channel]}`);
      }
      if (!fitsWireFloat(value)) {
        throw new MaxlError('MOVE_INVALID', `evaluator returned ${String(value)} at t = ${t.toFixed(4)} s; it must return a finite number within ±3.4e38`, `eventChannels.${channels[spec.channel]}`);
      }
      if (values.length === 0 || values[values.length - 1] !== value) {
        times.push(t);
        values.push(value);
      }
    }
    return { channel: spec.channel, times, values };
  });
}
