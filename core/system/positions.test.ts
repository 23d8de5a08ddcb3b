/**
 * Each preset runs a job end to end, real firmware in wasm behind simulated links:
 * every motor's executed position follows the plan within one step at all times,
 * once the clock mapping is accounted for.
 *
 * A board runs the plan in its own clock, through the author's model of it; where
 * that model is off by e µs, the motor is where the plan was e µs earlier or later,
 * v·e away. The model's error is tested on its own (clockSync.test.ts,
 * core/system/clocks.test.ts, npm run bench -- sync); here, the allowance is
 * v·(|e| + 25 µs), e read from the simulator's true clock at that moment and 25 µs
 * for the model refitted between a segment's transmission and its execution. What
 * remains, one step, is the firmware's own execution: evaluation and step generation.
 */
import { describe, expect, it } from 'vitest';
import { accelRig, blotPlotter, lightPainter } from '../sim/presets/index.ts';
import { motorTracks, planned, runAndCheckPositions, startMachine } from './harness.ts';

const square = (x0: number, y0: number, s: number) => [
  { endPosition: [x0 + s, y0] },
  { endPosition: [x0 + s, y0 + s] },
  { endPosition: [x0, y0 + s] },
  { endPosition: [x0, y0] },
];

describe('end to end: executed positions follow the plan within one step, given the clock mapping', () => {
  it.each([
    ['blotPlotter', blotPlotter, [{ endPosition: [5, 5] }, ...square(5, 5, 30), { endPosition: [40, 12] }, { endPosition: [7, 33] }]],
    ['lightPainter', lightPainter, [{ endPosition: [20, 20] }, ...square(20, 20, 60)]],
    ['accelRig', accelRig, [{ endPosition: [80] }, { endPosition: [10] }, { endPosition: [120] }, { endPosition: [0] }]],
  ])('%s', async (_name, preset, moves) => {
    const b = await startMachine(preset());
    const { worstExcess, worstSteps, samples, moving } = await runAndCheckPositions(b, moves as never);
    const motors = motorTracks(b);
    expect(moving).toBeGreaterThan(1000); // sampled every 0.25 ms through more than 0.25 s of motion
    expect(samples).toBeGreaterThan(2000);
    expect(worstExcess).toBeLessThanOrEqual(0);
    expect(worstSteps).toBeLessThan(4); // and in plain steps, never far off
    // The job really went somewhere, and ended where the plan ended.
    const end = b.sim.plant.motorSteps();
    for (const m of motors) expect(end[m.motor] / m.stepsPerMm).toBeCloseTo(planned(b, m.track, b.scheduler.now()), 1);
    expect(b.events.filter((e) => e.type === 'error')).toEqual([]);
    await b.maxl.end();
    await b.sim.stop();
  }, 60_000);
});
