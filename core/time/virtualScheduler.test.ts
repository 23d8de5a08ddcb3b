import { describe, expect, it } from 'vitest';
import { VirtualScheduler } from './virtualScheduler.ts';

describe('VirtualScheduler', () => {
  it('runs timers in time order, ties in the order set, and settles promises between them', async () => {
    const s = new VirtualScheduler(1000);
    const log: string[] = [];
    s.at(3000, () => log.push(`c@${s.now()}`));
    s.at(2000, () => {
      log.push(`a@${s.now()}`);
      // A promise chain started by a timer completes before the next timer runs.
      void Promise.resolve()
        .then(() => Promise.resolve())
        .then(() => log.push(`a-then@${s.now()}`));
    });
    s.at(2000, () => log.push(`b@${s.now()}`));
    const t = s.after(500, () => log.push('cancelled'));
    t.cancel();
    await s.runUntil(10_000);
    expect(log).toEqual(['a@2000', 'a-then@2000', 'b@2000', 'c@3000']);
    expect(s.now()).toBe(10_000);
  });

  it('moves data through web streams at the virtual instant it is written', async () => {
    const s = new VirtualScheduler();
    let controller!: ReadableStreamDefaultController<Uint8Array>;
    const readable = new ReadableStream<Uint8Array>({ start: (c) => (controller = c) });
    const got: Array<[number, number]> = [];
    void (async () => {
      const reader = readable.getReader();
      for (;;) {
        const { value, done } = await reader.read();
        if (done) return;
        got.push([s.now(), value[0]]);
      }
    })();
    for (let k = 1; k <= 3; k++) s.at(k * 1_000_000, () => controller.enqueue(Uint8Array.of(k)));
    await s.runUntil(3_600_000_000); // an hour
    expect(got).toEqual([
      [1_000_000, 1],
      [2_000_000, 2],
      [3_000_000, 3],
    ]);
  });

  it('sleeps in virtual time', async () => {
    const s = new VirtualScheduler();
    let woke = -1;
    void s.sleep(250).then(() => (woke = s.now()));
    await s.runUntil(1000);
    expect(woke).toBe(250);
  });
});
