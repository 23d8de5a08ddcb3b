/** The wall clock: author µs from performance.now(), timers from setTimeout. */
import { RecentWorst } from './recentWorst.ts';
import { BaseScheduler, type Timer } from './scheduler.ts';

/**
 * How far back (µs) the timers' lateness is remembered: a busy machine holds a
 * thread back again within seconds; a quiet one gets its short lead back this
 * long after the last hold-back.
 */
export const LATENESS_WINDOW_US = 10_000_000;

export class RealScheduler extends BaseScheduler {
  private readonly origin = performance.now();
  /**
   * How late every timer came: the thread's hold-backs (a busy machine, another
   * task of the same thread, a browser's timer clamp), whoever's timer saw them.
   * Pings, reads and pumps all run here, so a hold-back between two pumps still
   * counts (core/net/streamer.ts adds it to the lead).
   */
  private readonly lateness = new RecentWorst(LATENESS_WINDOW_US);

  now(): number {
    return (performance.now() - this.origin) * 1000;
  }

  at(at_us: number, callback: () => void): Timer {
    const handle = setTimeout(
      () => {
        this.lateness.noteLateness(at_us, this.now());
        callback();
      },
      Math.max(0, (at_us - this.now()) / 1000),
    );
    return { cancel: () => clearTimeout(handle) };
  }

  recentLateness_us(since_us: number): number {
    return this.lateness.worst(this.now(), since_us);
  }
}
