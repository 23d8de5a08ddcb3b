/**
 * npm run bench -- latency
 *
 * Stream latency: from addSegmentToQueue on an idle machine to the moment the
 * reader starts that motion, over a simulated USB link (round trip about 2 ms),
 * real firmware in wasm, virtual time.
 *
 * Ground truth: the simulator's time of the motor's first step, minus the time the
 * plan takes from rest to that step (physics, not latency): the step helper keeps
 * the motor at the nearest step, so the first comes at half a step of travel. Repeated from
 * rest at random moments (so USB frame phases vary); median and worst are given.
 * Target: streamLatencyMs ≤ 2·rttMs + 1. (Klipper starts moves 250 ms ahead; the
 * MAXL prototype 500 ms.)
 */
import { createMAXL } from '../core/index.ts';
import { VirtualScheduler } from '../core/time/virtualScheduler.ts';
import { createSimulatedMachine } from '../core/sim/machine.ts';
import { nodeWasmLoader } from '../core/sim/device/nodeWasmLoader.ts';
import { accelRig } from '../core/sim/presets/index.ts';
import { seededRandom } from '../core/random.ts';
import { evaluateTiming } from '../core/plan/phases.ts';
import type { SegmentView } from '../core/index.ts';

const TRIALS = Number(process.env.TRIALS ?? 40);
const random = seededRandom(5);
const scheduler = new VirtualScheduler();
const preset = accelRig();
const sim = await createSimulatedMachine(preset, scheduler, { seed: 5, loader: nodeWasmLoader() });
const maxl = createMAXL(sim.config, { links: Object.values(sim.links), scheduler });
const ready = maxl.begin();
// begin() takes its clock sync (2 s) and the hellos before it: run virtual time until it is done.
let begun = false;
void ready.then(() => (begun = true));
await scheduler.runWhile(() => !begun, 10_000_000);
await ready;
const stepsPerMm = preset.plant.motors[0].stepsPerMm;

let lastSeg: SegmentView | null = null;
maxl.queue.subscribe((e) => {
  if (e.type === 'transmitted' && lastSeg === null) lastSeg = e.segments[0]; // the move's first (maybe sliced) segment
});

/** Time (s) for the segment's path to reach `distance` mm from its start. */
function timeToReach(seg: SegmentView, distance: number): number {
  let lo = 0;
  let hi = seg.duration_s;
  const state = { s: 0, v: 0, a: 0 };
  for (let k = 0; k < 60; k++) {
    const mid = (lo + hi) / 2;
    if (evaluateTiming(seg.timing!, mid, state).s < distance) lo = mid;
    else hi = mid;
  }
  return hi;
}

const latencies: number[] = [];
let x = 0;
for (let trial = 0; trial < TRIALS; trial++) {
  // From rest, at a random moment (USB frames and the device loop at any phase).
  await scheduler.advance(200_000 + random() * 50_000);
  sim.sync();
  const steps0 = sim.plant.motorSteps().x;
  x = x === 0 ? 20 : 0;
  const t0 = scheduler.now();
  lastSeg = null;
  void maxl.addSegmentToQueue({ endPosition: [x] });
  // Watch for the first step, µs by µs.
  let firstStep = NaN;
  for (let t = t0; t < t0 + 50_000; t += 5) {
    await scheduler.runUntil(t);
    sim.sync();
    if (sim.plant.motorSteps().x !== steps0) {
      firstStep = t;
      break;
    }
  }
  const seg = lastSeg as SegmentView | null;
  if (!seg || Number.isNaN(firstStep)) throw new Error(`trial ${trial}: no motion within 50 ms`);
  const started = firstStep - timeToReach(seg, 0.5 / stepsPerMm) * 1e6;
  latencies.push((started - t0) / 1000);
  if (process.env.DEBUG) console.error('trial', trial, 'planned start − t0', ((seg.startTime_us - t0)/1000).toFixed(3), 'ms; device started − planned', ((started - seg.startTime_us)/1000).toFixed(3), 'ms');
  let idle = false;
  void maxl.whenIdle().then(() => (idle = true));
  await scheduler.runWhile(() => !idle, scheduler.now() + 5_000_000);
}
latencies.sort((a, b) => a - b);
const rtts = maxl.devices().map((d) => d.rtt_us);
const rttMs = Math.max(...rtts) / 1000;
const result = {
  bench: 'latency',
  streamLatencyMs: +latencies[latencies.length >> 1].toFixed(3),
  streamLatencyWorstMs: +latencies[latencies.length - 1].toFixed(3),
  streamLatencyBestMs: +latencies[0].toFixed(3),
  rttMs: +rttMs.toFixed(3),
  targetMs: +(2 * rttMs + 1).toFixed(3),
  trials: TRIALS,
  startLeadMs: +(((maxl as unknown as { runtime: { startLead_us: number } }).runtime.startLead_us) / 1000).toFixed(3),
};
await maxl.end();
await sim.stop();
console.log(JSON.stringify(result));
