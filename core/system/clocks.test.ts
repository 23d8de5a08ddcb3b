/**
 * Clock sync end to end: the real firmware's ping replies over a simulated USB
 * link with drift and asymmetric jitter, against the simulator's true clock.
 * (The full hour, three boards, is `npm run bench -- sync`.)
 */
import { describe, expect, it } from 'vitest';
import { blotPlotter } from '../sim/presets/index.ts';
import { startMachine } from './harness.ts';

describe('clock sync under drift and jitter', () => {
  it.each([
    ['a fast crystal, +190 ppm', 190],
    ['a slow crystal, −170 ppm, counter wrapping early on', -170],
  ])('%s', async (_what, ppm) => {
    const offset = ppm > 0 ? 1_000_000 : 2 ** 32 - 20_000_000; // the second wraps 20 s in
    const b = await startMachine(blotPlotter(), {
      seed: 11,
      sim: {
        clocks: { blot: { offset_us: offset, ppm } },
        links: {
          blot: {
            toDevice: { baseDelay_us: 200, jitterMin_us: 100, jitterMax_us: 1500 },
            toAuthor: { baseDelay_us: 200, jitterMin_us: 100, jitterMax_us: 600 },
          },
        },
      },
    });
    const session = (b.maxl as unknown as { runtime: { sessions: Array<{ clock: { clock: { rate: number; toDeviceExact(t: number): number } } }> } }).runtime.sessions[0];
    const truth = b.sim.devices.blot.clock;
    const early: number[] = [];
    const later: number[] = [];
    for (let t = b.scheduler.now(); t < 120e6; t += 250_000) {
      await b.scheduler.runUntil(t);
      const e = Math.abs(session.clock.clock.toDeviceExact(t + 10_000) - truth.deviceTimeAt(t + 10_000));
      (t < 30e6 ? early : later).push(e);
    }
    const p99 = (x: number[]) => [...x].sort((p, q) => p - q)[Math.floor(x.length * 0.99)];
    expect(Math.max(...early)).toBeLessThan(80); // from the first second of the session
    expect(p99(later)).toBeLessThan(20); // after half a minute
    expect(Math.abs(session.clock.clock.rate - 1 - ppm * 1e-6)).toBeLessThan(0.3e-6);
    await b.sim.stop();
  }, 120_000);
});
