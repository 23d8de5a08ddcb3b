/**
 * A validated move: what moves.ts makes of a move request, and what each of its
 * segments keeps as its `source` (segment.ts). In a file of its own so that both
 * can import it without importing each other.
 */
import type { ResolvedEventSpec } from './events.ts';

/**
 * A move that passed validation, not yet turned into segments. Its segments keep it
 * (as their `source`) for as long as they are queued.
 *
 * A class rather than an object literal, like every object that lives with a queued
 * segment: V8 may "pretenure" an object literal whose objects all survive a young
 * collection (as they do while the queue fills), and then creates them in the old
 * generation, where each keeps the young objects it points at alive until the next
 * full collection. Class instances carry no such allocation site.
 */
export class ValidatedMove {
  /** Where the move ends; for a dwell, where it was validated to start (a dwell holds wherever the path is). */
  readonly end: number[];
  readonly maxVelocity: number;
  readonly events: ResolvedEventSpec[];
  /** s, for a dwell; null for a linear move. */
  readonly dwell_s: number | null;
  /** mm/s², a cap on this move's acceleration (as Klipper's M204); Infinity for the machine's limits. */
  readonly maxAcceleration: number;
  /** The actuators at `end`, computed once by validation (null for a dwell). */
  readonly actuatorEnd: number[] | null;

  constructor(
    end: number[],
    maxVelocity: number,
    events: ResolvedEventSpec[],
    dwell_s: number | null = null,
    maxAcceleration = Infinity,
    actuatorEnd: number[] | null = null,
  ) {
    this.end = end;
    this.maxVelocity = maxVelocity;
    this.events = events;
    this.dwell_s = dwell_s;
    this.maxAcceleration = maxAcceleration;
    this.actuatorEnd = actuatorEnd;
  }
}
