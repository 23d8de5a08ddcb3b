/**
 * Byte corruption on both directions of the link: frames fail their CRC, are
 * nacked and sent again, and the machine executes the same trajectory as on a
 * clean link: the same segments with the same timing, each followed within a step,
 * to the same end.
 */
import { expect, it } from 'vitest';
import { blotPlotter } from '../sim/presets/index.ts';
import type { Segment } from '../trajectory/segment.ts';
import { runAndCheckPositions, startMachine } from './harness.ts';
import { queueOf } from '../maxl.ts';

const MOVES = [[20, 5], [40, 30], [10, 40], [35, 12], [5, 5]].map((p) => ({ endPosition: p, eventChannels: { pen: 1 } }));

async function run(corruption: number) {
  const b = await startMachine(blotPlotter(), {
    seed: 21,
    sim: { links: { blot: { toDevice: { corruptionProbability: corruption }, toAuthor: { corruptionProbability: corruption } } } },
  });
  const sent: Segment[] = [];
  queueOf(b.maxl).subscribe((e) => {
    if (e.type === 'transmitted') sent.push(...e.segments);
  });
  const check = await runAndCheckPositions(b, MOVES);
  const report = b.sim.linkReports().blot;
  const resends = (b.maxl as unknown as { runtime: { sessions: Array<{ resends: number }> } }).runtime.sessions[0].resends;
  // The transmitted trajectory as a function of time since its start, every millisecond.
  // (Its segments can differ: long ones are locked in slices cut where the lead time falls.)
  const first = sent[0].startTime_us;
  const last = sent[sent.length - 1].endTime_us;
  const plan: number[][] = [];
  for (let t = first; t <= last; t += 1000) plan.push(b.maxl.sample(t).position);
  const result = { check, plan, end: b.sim.plant.motorSteps(), corrupted: report.toDevice.bytesCorrupted + report.toAuthor.bytesCorrupted, resends, errors: b.events.filter((e) => e.type === 'error') };
  await b.sim.stop();
  return result;
}

it('after corruption, retransmission gives the same executed trajectory', async () => {
  const clean = await run(0);
  const noisy = await run(2e-4); // one byte in 5000: about one frame in 150
  expect(noisy.corrupted).toBeGreaterThan(5);
  expect(noisy.resends).toBeGreaterThan(0);
  expect(noisy.errors).toEqual([]);
  // The same trajectory was transmitted: the same positions at the same times since the start.
  expect(noisy.plan.length).toBe(clean.plan.length);
  clean.plan.forEach((p, k) => p.forEach((v, i) => expect(noisy.plan[k][i]).toBeCloseTo(v, 6)));
  // Both runs followed it within a step (plus the clock allowance), and ended at the same step.
  for (const r of [clean, noisy]) {
    expect(r.check.moving).toBeGreaterThan(1000);
    expect(r.check.worstExcess).toBeLessThanOrEqual(0);
  }
  expect(noisy.end).toEqual(clean.end);
}, 120_000);
