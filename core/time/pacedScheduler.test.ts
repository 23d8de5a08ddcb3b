import { describe, expect, it } from 'vitest';
import { PacedScheduler } from './pacedScheduler.ts';
import { settle } from './virtualScheduler.ts';

/** A hand-driven wall clock and wake timer, so the test decides when wall time passes. */
function harness() {
  let wall = 1_000_000; // µs; the scheduler's time starts at 0 from here
  const wakes: Array<{ delay_ms: number; callback: () => void; cancelled: boolean }> = [];
  const s = new PacedScheduler({
    wallNow: () => wall,
    wake: (delay_ms, callback) => {
      const w = { delay_ms, callback, cancelled: false };
      wakes.push(w);
      return { cancel: () => (w.cancelled = true) };
    },
  });
  return {
    s,
    pending: () => wakes.filter((w) => !w.cancelled),
    /** Moves the wall clock on and fires the pending wake, as the browser would. */
    async passWall(us: number) {
      wall += us;
      const live = wakes.filter((w) => !w.cancelled);
      wakes.length = 0;
      for (const w of live) w.callback();
      do await settle();
      while (s.driving);
    },
  };
}

describe('PacedScheduler', () => {
  it('runs each timer at its exact virtual time, in order, once the wall clock has passed it', async () => {
    const { s, passWall } = harness();
    const seen: Array<[string, number]> = [];
    s.at(3_500, () => seen.push(['b', s.now()]));
    s.at(1_250, () => seen.push(['a', s.now()]));
    s.at(9_000, () => seen.push(['c', s.now()]));
    await passWall(4_000);
    expect(seen).toEqual([
      ['a', 1_250],
      ['b', 3_500],
    ]);
    expect(s.now()).toBe(4_000); // caught up with the wall
    await passWall(6_000);
    expect(seen.at(-1)).toEqual(['c', 9_000]);
  });

  it('runs a chain of short timers set from callbacks at their own times, however coarse the wakes', async () => {
    const { s, passWall } = harness();
    const times: number[] = [];
    const hop = () => {
      times.push(s.now());
      if (times.length < 40) s.after(100, hop); // a device loop every 100 µs
    };
    s.after(100, hop);
    await passWall(4_000); // one wake, as a clamped setTimeout would give
    expect(times).toEqual(Array.from({ length: 40 }, (_, i) => 100 * (i + 1)));
  });

  it('moves its wake earlier when a sooner timer is set between wakes', () => {
    const { s, pending } = harness();
    s.at(50_000, () => {});
    expect(pending().map((w) => w.delay_ms)).toEqual([50]);
    s.at(2_000, () => {});
    expect(pending().map((w) => w.delay_ms)).toEqual([2]);
  });

  it('runs nothing after stop()', async () => {
    const { s, passWall } = harness();
    let ran = false;
    s.at(1_000, () => (ran = true));
    s.stop();
    await passWall(5_000);
    expect(ran).toBe(false);
  });

  it('logs a wake that fired late (the thread was starved), and not one on time', async () => {
    const { s, passWall } = harness();
    s.at(1_000, () => {});
    await passWall(2_000); // 1 ms late: not a stall
    expect(s.stalls).toEqual([]);
    s.at(3_000, () => {});
    await passWall(30_000); // the wake came 29 ms after its timer was due
    expect(s.stalls).toHaveLength(1);
    expect(s.stalls[0]).toMatchObject({ at_us: 3_000, late_ms: 29 });
  });
});
