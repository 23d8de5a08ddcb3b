/** The wall clock: author µs from performance.now(), timers from setTimeout. */
import { BaseScheduler, type Timer } from './scheduler.ts';

export class RealScheduler extends BaseScheduler {
  private readonly origin = performance.now();

  now(): number {
    return (performance.now() - this.origin) * 1000;
  }

  at(at_us: number, callback: () => void): Timer {
    const handle = setTimeout(callback, Math.max(0, (at_us - this.now()) / 1000));
    return { cancel: () => clearTimeout(handle) };
  }
}
