/**
 * Time for the runtime: a clock in author µs and timers on it. Two
 * implementations share this interface:
 *   - VirtualScheduler: deterministic virtual time for Node tests and benchmarks
 *     (an hour of machine time runs in seconds);
 *   - RealScheduler: the wall clock, for real boards;
 *   - PacedScheduler: virtual time kept up with the wall clock, for a simulated
 *     machine in a browser worker (exact timers, real-time pace).
 * Runtime code (sessions, clock sync, streaming) only ever uses this interface.
 */
export interface Timer {
  cancel(): void;
}

export interface Scheduler {
  /** Author time, µs (float64). */
  now(): number;
  /** Runs `callback` at author time `at_us` (or as soon as possible if that has passed). */
  at(at_us: number, callback: () => void): Timer;
  /** Runs `callback` after `delay_us`. */
  after(delay_us: number, callback: () => void): Timer;
  /** Resolves after `delay_us`. */
  sleep(delay_us: number): Promise<void>;
  /**
   * On the wall clock only: the worst lateness (µs) of this scheduler's timers
   * that fired at or after `since_us`, over its recent window (RealScheduler):
   * how long its thread was held back lately. Virtual time is never late.
   */
  recentLateness_us?(since_us: number): number;
}

export abstract class BaseScheduler implements Scheduler {
  abstract now(): number;
  abstract at(at_us: number, callback: () => void): Timer;
  after(delay_us: number, callback: () => void): Timer {
    return this.at(this.now() + delay_us, callback);
  }
  sleep(delay_us: number): Promise<void> {
    return new Promise((resolve) => this.after(delay_us, resolve));
  }
}
