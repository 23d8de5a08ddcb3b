/**
 * Virtual time that keeps pace with the wall clock: for a simulated machine in a
 * browser worker, where the author and the simulated devices share one thread.
 *
 * With RealScheduler every timer is a setTimeout, which a browser delays by 1–4 ms
 * (more when the worker is busy). Each hop of a simulated exchange (author → link
 * → device loop → link → author) would pay that, so the simulated USB link, whose
 * round trip is ~2 ms, measured ~15 ms in the page, the sync error was ~1 ms, and
 * every lead time grew with it. Here the timers run on a VirtualScheduler instead,
 * each at its exact virtual time and in order; a driver wakes now and then and
 * runs every timer up to the wall clock. So the simulation sees exactly the link
 * it models, and virtual time trails the wall clock by at most one wake (a few ms)
 * plus the work done in it. `now()` between wakes is the time of the last one.
 *
 * Only for machines that are simulated end to end: a real board's clock runs on
 * the wall, and wants RealScheduler.
 */
import { BaseScheduler, type Timer } from './scheduler.ts';
import { VirtualScheduler } from './virtualScheduler.ts';

export interface PacedSchedulerOptions {
  /** Wall clock, µs (default performance.now()). */
  wallNow?: () => number;
  /** Runs `callback` after about `delay_ms` of wall time (default setTimeout). */
  wake?: (delay_ms: number, callback: () => void) => Timer;
}

/**
 * A wake that fired more than STALL_MS after its timer was due, or whose timers took
 * more than STALL_MS of wall time to run: meanwhile virtual time stood still while
 * the wall clock ran on, so anything the page timestamped then lands on the author's
 * clock ahead of the simulation by up to late_ms + run_ms.
 */
export interface PacingStall {
  /** Virtual µs the wake ran timers from. */
  at_us: number;
  /** ms from the earliest due timer's time to the wake (wall). */
  late_ms: number;
  /** ms of wall time the wake spent running timers. */
  run_ms: number;
}

const STALL_MS = 5;
const STALLS_KEPT = 2000;

export class PacedScheduler extends BaseScheduler {
  private readonly virtual: VirtualScheduler;
  private readonly wallNow: () => number;
  private readonly wake: (delay_ms: number, callback: () => void) => Timer;
  /** Virtual time minus wall time, fixed at construction (both start together). */
  private readonly origin: number;
  private wakeTimer: Timer | null = null;
  /** Virtual time the pending wake is for. */
  private wakeAt = Infinity;
  private running = false;
  private stopped = false;
  /** The wakes that came late or ran long (newest STALLS_KEPT), for benches that must tell a starved thread from a slow machine. */
  private readonly stallLog: PacingStall[] = [];

  constructor(options: PacedSchedulerOptions = {}) {
    super();
    this.wallNow = options.wallNow ?? (() => performance.now() * 1000);
    this.wake =
      options.wake ??
      ((delay_ms, callback) => {
        const handle = setTimeout(callback, delay_ms);
        return { cancel: () => clearTimeout(handle) };
      });
    this.origin = this.wallNow();
    this.virtual = new VirtualScheduler(0);
  }

  now(): number {
    return this.virtual.now();
  }

  at(at_us: number, callback: () => void): Timer {
    const timer = this.virtual.at(at_us, callback);
    if (!this.running) this.armWake();
    return timer;
  }

  /**
   * The virtual time a wall time stands for (both µs; wall time on wallNow's scale,
   * performance.now() by default): the pace's fixed offset. Virtual time runs at
   * the wall clock's rate and trails it by at most one wake, so an event the page
   * timestamped (performance.timeOrigin + event.timeStamp, mapped into this
   * context's performance.now()) lands on the author's clock here.
   */
  virtualTimeAtWall(wall_us: number): number {
    return wall_us - this.origin;
  }

  /** The wall clock, on the virtual time's scale (µs). */
  private wallTime(): number {
    return this.wallNow() - this.origin;
  }

  /** Whether a wake is running timers now. */
  get driving(): boolean {
    return this.running;
  }

  /** Stops driving: pending timers never run. */
  stop(): void {
    this.stopped = true;
    this.wakeTimer?.cancel();
    this.wakeTimer = null;
  }

  /** Sets the wake for the earliest pending timer, if it is earlier than the one set. */
  private armWake(): void {
    if (this.stopped) return;
    const next = this.virtual.nextAt();
    if (next === Infinity || next >= this.wakeAt) return;
    this.wakeTimer?.cancel();
    this.wakeAt = next;
    this.wakeTimer = this.wake(Math.max(0, (next - this.wallTime()) / 1000), () => void this.drive());
  }

  /** Runs every timer due by the wall clock, each at its own virtual time. */
  private async drive(): Promise<void> {
    this.wakeTimer = null;
    this.wakeAt = Infinity;
    if (this.running || this.stopped) return;
    this.running = true;
    const from_us = this.virtual.now();
    const due = this.virtual.nextAt();
    const start = this.wallTime();
    try {
      await this.virtual.runUntil(Math.max(start, from_us));
    } finally {
      this.running = false;
    }
    const late_ms = due === Infinity ? 0 : Math.max(0, (start - due) / 1000);
    const run_ms = (this.wallTime() - start) / 1000;
    if (late_ms > STALL_MS || run_ms > STALL_MS) {
      if (this.stallLog.length >= STALLS_KEPT) this.stallLog.shift();
      this.stallLog.push({ at_us: Math.max(from_us, due === Infinity ? from_us : due), late_ms, run_ms });
    }
    this.armWake();
  }

  /** The wakes that came late or ran long so far (oldest first; the newest 2000). */
  get stalls(): readonly PacingStall[] {
    return this.stallLog;
  }
}
