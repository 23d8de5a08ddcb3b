/**
 * Where the transmitted path ends (queue.ts): the author µs at which its last
 * segment ends, the speed² the machine still has there, the event channels' values
 * there, and the path's tail there (position, direction, cruise cap), copied when
 * a segment is locked.
 *
 * The next segment transmitted starts where the transmitted path ends if the
 * machine is still moving there, else no earlier than its executor allows. An edit
 * of the first untransmitted move starts again from the recorded tail, as the last
 * transmitted segment itself may no longer be held. The tail is unknown before
 * anything is transmitted and after a restart (the untransmitted path then starts
 * from rest).
 */
import type { PathTail } from './moves.ts';

export class TransmittedEnd {
  /** Author µs at which the transmitted path ends; −∞ before anything is transmitted. */
  end_us = -Infinity;
  /** Speed² (mm²/s²) at which it ends. */
  exit2 = 0;
  /** Every event channel's value at its end (a new array whenever one changes: segments keep it as their eventsAtStart). */
  eventValues: number[];
  private tailKnown = false;
  private readonly position: number[];
  private readonly unit: number[];
  private hasUnit = false;
  private cruise2 = 0;

  constructor(axes: number, channels: number) {
    this.eventValues = new Array<number>(channels).fill(0);
    this.position = new Array<number>(axes).fill(0);
    this.unit = new Array<number>(axes).fill(0);
  }

  /** Author µs at which a segment transmitted now starts, given the earliest start its executor allows. */
  nextStart_us(earliestStart_us: number): number {
    return this.exit2 > 0 ? this.end_us : Math.max(earliestStart_us, this.end_us);
  }

  /**
   * A segment was locked: the transmitted path now ends at `end_us`, at speed² `exit2`,
   * at `end` along `unit` (null: at rest, after a dwell) with cruise cap `cruise2`
   * (copied, so later appends and locks cannot change them).
   */
  lock(end_us: number, exit2: number, end: readonly number[], unit: readonly number[] | null, cruise2: number): void {
    this.end_us = end_us;
    this.exit2 = exit2;
    for (let i = 0; i < end.length; i++) this.position[i] = end[i];
    this.hasUnit = unit !== null;
    if (unit !== null) for (let i = 0; i < unit.length; i++) this.unit[i] = unit[i];
    this.cruise2 = cruise2;
    this.tailKnown = true;
  }

  /** Sets `tail` to the path's tail at the transmitted path's end (new arrays) and returns true; false, changing nothing, if it is unknown. */
  restoreTail(tail: PathTail): boolean {
    if (!this.tailKnown) return false;
    tail.position = [...this.position];
    tail.unit = this.hasUnit ? [...this.unit] : null;
    tail.cruise2 = this.cruise2;
    return true;
  }

  /** The machine stopped off its plan (a restart): it is at rest, the tail is unknown, and the channels hold `eventValues`. */
  restart(eventValues: number[]): void {
    this.exit2 = 0;
    this.tailKnown = false;
    this.eventValues = eventValues;
  }
}
