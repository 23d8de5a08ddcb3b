/**
 * Pointer input, released to the drawer in the order and at the time it was made.
 *
 * On a simulated machine the author and the simulated boards share the worker's
 * thread, on a paced clock (core/time/pacedScheduler.ts): when the thread is
 * starved, virtual time stands still while the wall clock runs on, then catches up
 * in a burst. The page's pointer events meanwhile carry their own times (mapped
 * exactly onto the author's clock), and between the burst's timers the worker
 * handles the messages that waited. Without this, a point made at author time t
 * would reach the drawer while the simulation is still before t: the machine
 * would know where the pen goes before the pen went there, and every lag read
 * short by as much.
 *
 * So an input stamped ahead of the author's clock waits here until the clock
 * reaches its stamp; one stamped at or before it (the usual case: it took a
 * message's latency to get here, which counts as real lag) goes at once. Inputs
 * never overtake one another: one behind a waiting input waits too, and an input
 * without a time of its own (the pointer lifting) goes after the one before it.
 *
 * A real board's clock is the wall clock: nothing is ever ahead of it, and this
 * passes every input straight through.
 */
import type { Scheduler, Timer } from '../../../../core/index.ts';

interface Pending {
  at_us: number;
  run: () => void;
}

export class PointerTimeline {
  private readonly pending: Pending[] = [];
  private timer: Timer | null = null;

  constructor(private readonly scheduler: () => Scheduler) {}

  /** Runs `run` once the author's clock reaches `at_us` (NaN: right after the input before it). */
  push(at_us: number, run: () => void): void {
    const last = this.pending.at(-1);
    const at = Number.isNaN(at_us) ? (last?.at_us ?? -Infinity) : Math.max(at_us, last?.at_us ?? -Infinity);
    if (this.pending.length === 0 && at <= this.scheduler().now()) {
      run();
      return;
    }
    this.pending.push({ at_us: at, run });
    this.arm();
  }

  /** Inputs waiting for their time. */
  get waiting(): number {
    return this.pending.length;
  }

  /** Forgets every waiting input (STOP, or another machine). */
  clear(): void {
    this.pending.length = 0;
    this.timer?.cancel();
    this.timer = null;
  }

  private arm(): void {
    if (this.timer || this.pending.length === 0) return;
    this.timer = this.scheduler().at(this.pending[0].at_us, () => {
      this.timer = null;
      this.release();
    });
  }

  private release(): void {
    const now = this.scheduler().now();
    while (this.pending.length > 0 && this.pending[0].at_us <= now) (this.pending.shift() as Pending).run();
    this.arm();
  }
}
