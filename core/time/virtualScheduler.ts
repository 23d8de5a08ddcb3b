/**
 * Deterministic virtual time. Timers run in time order (ties in the order they
 * were set); after each one, every promise continuation it caused settles before
 * time moves on, so async code (streams, awaits) behaves exactly as it would in
 * real time, only without waiting. The same seed and the same calls give the same
 * run, byte for byte.
 */
import { BaseScheduler, type Timer } from './scheduler.ts';

interface Entry {
  at: number;
  order: number;
  callback: () => void;
  cancelled: boolean;
}

/**
 * Lets every pending promise continuation run: one macrotask turn, after the
 * microtask queue has drained. setImmediate where there is one (Node): unlike
 * setTimeout(0), which Node clamps to 1 ms of real time per call, it costs
 * microseconds, so an hour of virtual time stays fast. A MessageChannel turn
 * elsewhere.
 */
export const settle: () => Promise<void> =
  typeof setImmediate === 'function'
    ? () => new Promise((resolve) => setImmediate(resolve))
    : (() => {
        const channel = new MessageChannel();
        const waiting: Array<() => void> = [];
        channel.port1.onmessage = () => waiting.shift()?.();
        return () =>
          new Promise<void>((resolve) => {
            waiting.push(resolve);
            channel.port2.postMessage(0);
          });
      })();

export class VirtualScheduler extends BaseScheduler {
  private time: number;
  private order = 0;
  /** A binary min-heap on (at, order). */
  private heap: Entry[] = [];

  constructor(start_us = 0) {
    super();
    this.time = start_us;
  }

  now(): number {
    return this.time;
  }

  at(at_us: number, callback: () => void): Timer {
    const entry: Entry = { at: Math.max(at_us, this.time), order: this.order++, callback, cancelled: false };
    this.push(entry);
    return { cancel: () => (entry.cancelled = true) };
  }

  /** Time of the next timer, or Infinity. */
  nextAt(): number {
    while (this.heap.length > 0 && this.heap[0].cancelled) this.pop();
    return this.heap.length > 0 ? this.heap[0].at : Infinity;
  }

  /** Runs every timer due up to `end_us` in order, settling promises after each, then sets the clock to `end_us`. */
  async runUntil(end_us: number): Promise<void> {
    await settle();
    for (;;) {
      const next = this.nextAt();
      if (next > end_us) break;
      const entry = this.pop() as Entry;
      this.time = entry.at;
      entry.callback();
      await settle();
    }
    if (end_us > this.time) this.time = end_us;
  }

  advance(delay_us: number): Promise<void> {
    return this.runUntil(this.time + delay_us);
  }

  /** Runs until `done()` holds (checked after every timer) or `limit_us` passes; returns whether it held. */
  async runWhile(busy: () => boolean, limit_us: number): Promise<boolean> {
    await settle();
    while (busy()) {
      const next = this.nextAt();
      if (next > limit_us) {
        this.time = Math.max(this.time, limit_us);
        return false;
      }
      const entry = this.pop() as Entry;
      this.time = entry.at;
      entry.callback();
      await settle();
    }
    return true;
  }

  private less(a: Entry, b: Entry): boolean {
    return a.at < b.at || (a.at === b.at && a.order < b.order);
  }

  private push(e: Entry): void {
    const h = this.heap;
    h.push(e);
    let i = h.length - 1;
    while (i > 0) {
      const p = (i - 1) >> 1;
      if (!this.less(h[i], h[p])) break;
      [h[i], h[p]] = [h[p], h[i]];
      i = p;
    }
  }

  private pop(): Entry | undefined {
    const h = this.heap;
    const top = h[0];
    const last = h.pop();
    if (h.length > 0 && last) {
      h[0] = last;
      let i = 0;
      for (;;) {
        const l = 2 * i + 1;
        const r = l + 1;
        let m = i;
        if (l < h.length && this.less(h[l], h[m])) m = l;
        if (r < h.length && this.less(h[r], h[m])) m = r;
        if (m === i) break;
        [h[i], h[m]] = [h[m], h[i]];
        i = m;
      }
    }
    return top;
  }
}
