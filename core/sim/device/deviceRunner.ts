/**
 * Runs every device of a simulated machine in one time order, in chunks.
 *
 * A device loop every 20 µs cannot be a scheduler timer each (setTimeout
 * cannot do it in real time, and in virtual time each timer has a cost), so
 * the runner keeps one timer for the whole machine and, when it fires at t,
 * runs every loop due up to t, across devices, earliest first (ties in device
 * order). That is `runTo(t)`. The timer is set for the next loop due, rounded
 * up to a chunk boundary (default 1 ms, the USB frame: bytes a device writes
 * inside a chunk would wait for the next frame anyway):
 *
 *   busy devices:  one timer per chunk, ~50 loops per device inside it;
 *   idle devices:  one timer per idle tick;
 *   bytes arrive:  the link's delivery calls `deliver`, which first runs
 *                  everything due before the arrival, then the receiving
 *                  device at the arrival time.
 *
 * So every input the plant sees (steps, LED frames, I2C reads) comes in time
 * order, whichever device made it. With a RealScheduler the timer fires late
 * by however much the browser likes, and runTo(now) catches up.
 */
import type { Scheduler, Timer } from '../../time/scheduler.ts';
import type { WasmDevice } from './wasmDevice.ts';

export class DeviceRunner {
  private timer: Timer | null = null;
  private wakeAt_us = Infinity;
  private stopped = false;
  /** Timer wake-ups so far (for benchmarks). */
  wakeups = 0;

  constructor(
    private readonly scheduler: Scheduler,
    readonly devices: WasmDevice[],
    readonly chunk_us = 1000,
    /** Called with any error a device raises while the runner's own timer runs it (else it is thrown). */
    private readonly onError?: (error: unknown) => void,
  ) {}

  /** Starts every device (static constructors and setup) at now, and the timer. */
  start(): void {
    const now = this.scheduler.now();
    for (const d of this.devices) d.start(now);
    this.runTo(now);
    this.arm();
  }

  /** Runs every device loop due at or before `t_us`, in time order. */
  runTo(t_us: number): void {
    for (;;) {
      let next: WasmDevice | null = null;
      for (const d of this.devices) {
        if (d.crashed) continue;
        if (d.nextLoop_us <= t_us && (next === null || d.nextLoop_us < next.nextLoop_us)) next = d;
      }
      if (next === null) return;
      next.step();
    }
  }

  /** Bytes arrive at `device` now: everything due before runs first. */
  deliver(device: WasmDevice, bytes: Uint8Array): void {
    if (this.stopped) return;
    const now = this.scheduler.now();
    this.guard(() => {
      this.runTo(now);
      device.receive(bytes, now);
    });
    this.arm();
  }

  /**
   * Puts `next` in place of `old` from now on (a board that restarted: a fresh
   * instance of its firmware), after everything due before now ran on the old one.
   */
  replace(old: WasmDevice, next: WasmDevice): void {
    const i = this.devices.indexOf(old);
    if (i < 0) throw new Error(`replace: ${old.name} is not run here`);
    const now = this.scheduler.now();
    this.guard(() => this.runTo(now));
    this.devices[i] = next;
    this.guard(() => {
      next.start(now);
      this.runTo(now);
    });
    this.arm();
  }

  /** Stops the timer; devices keep their state but run no more. */
  stop(): void {
    this.stopped = true;
    this.timer?.cancel();
    this.timer = null;
  }

  private guard(fn: () => void): void {
    try {
      fn();
    } catch (err) {
      if (!this.onError) throw err;
      this.onError(err);
    }
  }

  /** (Re)sets the one timer for the next chunk boundary at or after the earliest loop due. */
  private arm(): void {
    if (this.stopped) return;
    let next = Infinity;
    for (const d of this.devices) if (!d.crashed) next = Math.min(next, d.nextLoop_us);
    if (next === Infinity) return;
    const wake = Math.ceil(next / this.chunk_us) * this.chunk_us;
    if (wake === this.wakeAt_us && this.timer) return;
    this.timer?.cancel();
    this.wakeAt_us = wake;
    this.timer = this.scheduler.at(wake, () => {
      this.timer = null;
      this.wakeAt_us = Infinity;
      this.wakeups++;
      this.guard(() => this.runTo(this.scheduler.now()));
      this.arm();
    });
  }
}
