/**
 * Hold-to-jog needs a long move to be locked only a slice at a time, also while it
 * runs at speed (not only as it starts from rest): then a cancel brakes within a
 * few ms. Runs the simulated light painter (real firmware in wasm) in virtual time.
 */
import { describe, expect, it } from 'vitest';
import { createMAXL } from '../maxl.ts';
import { VirtualScheduler } from '../time/virtualScheduler.ts';
import { createSimulatedMachine } from '../sim/machine.ts';
import { nodeWasmLoader } from '../sim/device/nodeWasmLoader.ts';
import { lightPainter } from '../sim/presets/index.ts';

describe('streamer slicing of a long move (hold-to-jog)', () => {
  it('keeps the locked path within a few ms of now while a long move runs, so a cancel brakes at once', async () => {
    const scheduler = new VirtualScheduler();
    const sim = await createSimulatedMachine(lightPainter(), scheduler, { loader: nodeWasmLoader() });
    const maxl = createMAXL(sim.config, { links: Object.values(sim.links), scheduler });
    const begun = maxl.begin();
    await scheduler.advance(2_000_000);
    await begun;
    void maxl.addSegmentToQueue({ endPosition: [290, 0], maxVelocity: 50 });
    let worstAhead_us = 0;
    for (let i = 0; i < 20; i++) {
      await scheduler.advance(50_000);
      worstAhead_us = Math.max(worstAhead_us, maxl.queue.transmittedEnd_us - scheduler.now());
    }
    // lead (2·RTT + 1 ms) plus two slices of 4 ms at most: far below the 5.8 s move.
    expect(worstAhead_us).toBeLessThan(maxl.lead_us + 8_000 + 1_000);
    const released_us = scheduler.now();
    const speed = maxl.estimate().speed;
    expect(speed).toBeCloseTo(50, 3);
    const stopped = maxl.cancel();
    const brakeStart_us = maxl.queue.transmittedEnd_us;
    expect(brakeStart_us - released_us).toBeLessThan(maxl.lead_us + 8_000 + 1_000);
    await scheduler.advance(500_000);
    await stopped;
    // At rest on the path, well short of the move's end: 50 mm/s for 1 s from 0, plus braking.
    expect(maxl.estimate().speed).toBe(0);
    const x = maxl.estimate().position[0];
    expect(x).toBeGreaterThan(45);
    expect(x).toBeLessThan(55);
    await maxl.end();
    await sim.stop();
  });
});
