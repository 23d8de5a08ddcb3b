import { describe, expect, it } from 'vitest';
import { VirtualScheduler } from '../../../../core/index.ts';
import { PointerTimeline } from './pointerTimeline.ts';

describe('PointerTimeline', () => {
  it('holds an input stamped ahead of the clock until its time, and passes one at or behind it at once', async () => {
    const s = new VirtualScheduler(10_000);
    const seen: Array<[string, number]> = [];
    const line = new PointerTimeline(() => s);
    line.push(9_000, () => seen.push(['late', s.now()]));
    expect(seen).toEqual([['late', 10_000]]);
    line.push(12_500, () => seen.push(['ahead', s.now()]));
    expect(line.waiting).toBe(1);
    await s.runUntil(12_000);
    expect(seen).toHaveLength(1);
    await s.runUntil(13_000);
    expect(seen.at(-1)).toEqual(['ahead', 12_500]);
    expect(line.waiting).toBe(0);
  });

  it('never lets an input overtake one that waits, and releases an untimed one right after the one before', async () => {
    const s = new VirtualScheduler(0);
    const order: string[] = [];
    const line = new PointerTimeline(() => s);
    line.push(5_000, () => order.push('a'));
    line.push(1_000, () => order.push('b')); // stamped earlier, but behind a waiting input
    line.push(NaN, () => order.push('up'));
    line.push(7_000, () => order.push('c'));
    await s.runUntil(4_999);
    expect(order).toEqual([]);
    await s.runUntil(5_000);
    expect(order).toEqual(['a', 'b', 'up']);
    await s.runUntil(7_000);
    expect(order).toEqual(['a', 'b', 'up', 'c']);
  });

  it('forgets what waits on clear', async () => {
    const s = new VirtualScheduler(0);
    const order: string[] = [];
    const line = new PointerTimeline(() => s);
    line.push(5_000, () => order.push('a'));
    line.clear();
    await s.runUntil(10_000);
    expect(order).toEqual([]);
    expect(line.waiting).toBe(0);
  });
});
