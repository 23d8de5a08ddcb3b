/**
 * A job that crosses the 32-bit wrap of a board's µs counter (every 71.6 minutes)
 * behaves the same: positions follow the plan within one step across the wrap.
 */
import { expect, it } from 'vitest';
import { blotPlotter } from '../sim/presets/index.ts';
import { runAndCheckPositions, startMachine } from './harness.ts';

it('a job crossing the u32 micros wrap runs as any other', async () => {
  // The board's counter wraps 2.8 s after power-up: after begin() (2 s of clock sync), during the job below.
  const b = await startMachine(blotPlotter(), { sim: { clocks: { blot: { offset_us: 2 ** 32 - 2_800_000, ppm: -25 } } } });
  const clock = b.sim.devices.blot.clock;
  const before = clock.microsAt(b.scheduler.now());
  const moves = [[30, 0], [30, 30], [0, 30], [0, 0], [45, 20]].map((p) => ({ endPosition: p }));
  const { worstExcess, worstSteps, moving } = await runAndCheckPositions(b, moves);
  const after = clock.microsAt(b.scheduler.now());
  expect(before).toBeGreaterThan(2 ** 32 - 1_000_000); // before the job: just under 2³²
  expect(after).toBeLessThan(before); // after it: wrapped
  expect(moving).toBeGreaterThan(1000);
  expect(worstExcess).toBeLessThanOrEqual(0);
  expect(worstSteps).toBeLessThan(4);
  expect(b.events.filter((e) => e.type === 'error')).toEqual([]);
  await b.sim.stop();
}, 60_000);
