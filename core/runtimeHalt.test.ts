/**
 * halt() mid-job: every device gets HALT and stops where it is, even when the
 * queue still holds a path the machine is committed to (cancelAll would refuse it).
 * Runs the simulated light painter (real firmware in wasm) in virtual time.
 */
import { describe, expect, it } from 'vitest';
import { startMachine } from './system/harness.ts';
import { lightPainter } from './sim/presets/index.ts';

describe('halt mid-job', () => {
  it('halts every device, and their motors stop', async () => {
    const { scheduler, sim, maxl } = await startMachine(lightPainter());
    for (let i = 1; i <= 50; i++) void maxl.addSegmentToQueue({ endPosition: [i * 2, (i % 2) * 5] });
    await scheduler.advance(300_000);
    expect(maxl.estimate().speed).toBeGreaterThan(0);
    const halted = maxl.halt();
    await scheduler.advance(100_000);
    await halted;
    await scheduler.advance(300_000);
    expect(maxl.devices().map((d) => d.deviceState)).toEqual(['halted', 'halted', 'halted']);
    sim.sync();
    const steps = sim.plant.motorSteps();
    await scheduler.advance(1_000_000);
    sim.sync();
    expect(sim.plant.motorSteps()).toEqual(steps);
    await maxl.end();
    await sim.stop();
  });
});
