/**
 * Always stoppable (docs/design.md, decision 4): whenever links die mid-job, every reader
 * comes to rest on the path at v = 0, and the author says where.
 */
import { afterAll, describe, expect, it } from 'vitest';
import { blotPlotter, lightPainter } from '../sim/presets/index.ts';
import { seededRandom } from '../random.ts';
import { corneredPath, distanceToPolyline } from './geometry.ts';
import { startMachine, type Bench } from './harness.ts';

const PATH = corneredPath();

async function cutMidJob(b: Bench, cutAfter_us: number, which: string[]) {
  const start = b.maxl.queue.tailPosition as number[];
  for (const p of PATH) void b.maxl.addSegmentToQueue({ endPosition: p });
  await b.scheduler.advance(cutAfter_us);
  b.sim.sync();
  const speedAtCut = b.maxl.estimate().speed;
  for (const name of which) b.sim.cut(name);
  // Long enough to notice, brake and settle.
  await b.scheduler.advance(600_000);
  b.sim.sync();
  const stepsThen = b.sim.plant.motorSteps();
  await b.scheduler.advance(200_000);
  b.sim.sync();
  return { path: [start, ...PATH], speedAtCut, stepsThen, stepsNow: b.sim.plant.motorSteps(), carriage: b.sim.plant.carriage() };
}

const offPath: number[] = [];
afterAll(() => {
  if (offPath.length) console.log(`one motor board cut: carriage off the path by at most ${Math.max(...offPath).toFixed(3)} mm`);
});

describe('a link cut at a random moment', () => {
  const random = seededRandom(2026);
  const moments = Array.from({ length: 4 }, () => 1_100_000 + random() * 1_200_000);

  it.each(moments.map((m) => [Math.round(m / 1000), m]))('Blot plotter, one board: stops on the path at rest (cut %i ms after the job starts)', async (_ms, moment) => {
    const b = await startMachine(blotPlotter(), { seed: 3 });
    const r = await cutMidJob(b, moment, ['blot']);
    expect(r.speedAtCut).toBeGreaterThan(5); // it was moving when the cable went
    expect(r.stepsNow).toEqual(r.stepsThen); // v = 0
    // On the path: within a step or two of it (a step is 1/80 mm on each motor).
    expect(distanceToPolyline([r.carriage.x, r.carriage.y], r.path)).toBeLessThan(0.03);
    expect(b.events.some((e) => e.type === 'device' && e.text.includes('lost'))).toBe(true);
    await b.sim.stop();
  }, 60_000);

  it.each(moments.map((m) => [Math.round(m / 1000), m]))('light painter, every link at once: both motor boards stop at the same point of the path (cut %i ms in)', async (_ms, moment) => {
    const b = await startMachine(lightPainter(), { seed: 4 });
    const r = await cutMidJob(b, moment, ['motorA', 'motorB', 'lightPainter']);
    expect(r.speedAtCut).toBeGreaterThan(5);
    expect(r.stepsNow).toEqual(r.stepsThen);
    expect(distanceToPolyline([r.carriage.x, r.carriage.y], r.path)).toBeLessThan(0.03);
    await b.sim.stop();
  }, 60_000);

  it.each(moments.map((m) => [Math.round(m / 1000), m]))('light painter, one motor board cut: the other board stops with it, within the stall-limit motion of the path (cut %i ms in)', async (_ms, moment) => {
    const b = await startMachine(lightPainter(), { seed: 5 });
    const r = await cutMidJob(b, moment, ['motorA']);
    expect(r.speedAtCut).toBeGreaterThan(5);
    expect(r.stepsNow).toEqual(r.stepsThen);
    // Frames in flight when the one cable went may reach the other board: the boards
    // can stop apart by at most the motion of the streamer's stall limit (plus a step).
    const stall = (b.maxl as unknown as { runtime: { streamerStallLimit_us: number } }).runtime.streamerStallLimit_us;
    const bound = r.speedAtCut * stall * 1e-6 + 0.03;
    const off = distanceToPolyline([r.carriage.x, r.carriage.y], r.path);
    expect(off).toBeLessThan(bound);
    offPath.push(off);
    // The healthy boards said where they stopped.
    const stops = b.events.filter((e) => e.type === 'stopped');
    expect(stops.length).toBeGreaterThan(0);
    await b.sim.stop();
  }, 60_000);
});
