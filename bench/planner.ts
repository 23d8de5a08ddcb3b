/**
 * npm run bench -- planner
 *
 * Plans three 100 000-segment paths (bench/paths.ts) two ways:
 *  - incremental: through the queue, one awaited addSegmentToQueue per point (the
 *    paper's Listing 2), with a consumer that transmits (locks) the front segment
 *    whenever the queue is full, then drains it at the end; one MAXL per path,
 *    kept across runs as a workbench keeps it across jobs;
 *  - batch: planPath over the whole path.
 * Each is timed over several runs after warm-up runs; the median is reported. The
 * top-level segmentsPerSecond is the worst path's incremental rate.
 */
import os from 'node:os';
import { createMAXL, planPath } from '../core/index.ts';
import { benchPaths, BENCH_LIMITS, type BenchPath } from './paths.ts';
import { queueOf } from '../core/maxl.ts';

const RUNS = Number(process.env.BENCH_RUNS ?? 5);

/**
 * One machine per path, reused for every run, as a workbench keeps one MAXL across
 * jobs: its history ring is allocated and paged in once (the warm-up runs), so the
 * timed runs measure planning, not first-touch page faults. Each run starts the
 * path again from where the last ended (at rest).
 */
function machineFor(path: BenchPath) {
  return createMAXL({ motionAxes: ['x', 'y'], limits: BENCH_LIMITS }, { initialPosition: path.start });
}

async function incremental(maxl: ReturnType<typeof machineFor>, path: BenchPath): Promise<{ seconds: number; plannedDuration_s: number; segments: number }> {
  const q = queueOf(maxl);
  let plannedDuration = 0;
  let segments = 0;
  // The consumer a device session would be: lock the front segment, and retire what
  // has been executed (here: everything before it, as if time had moved on).
  const take = () => {
    const seg = q.transmitNext(0)!;
    q.retireUntil(seg.startTime_us);
    plannedDuration += seg.duration_s;
    segments++;
  };
  // Back to the start first (one move), so every run plans the same path from rest.
  await maxl.addSegmentToQueue({ endPosition: path.start });
  q.planToRest();
  while (q.untransmittedCount > 0) q.transmitNext(0);
  const t0 = performance.now();
  for (const p of path.points) {
    await maxl.addSegmentToQueue({ endPosition: p });
    if (!q.hasRoom()) take();
  }
  q.planToRest();
  while (q.untransmittedCount > 0) take();
  const seconds = (performance.now() - t0) / 1000;
  return { seconds, plannedDuration_s: plannedDuration, segments };
}

function batch(path: BenchPath): { seconds: number; plannedDuration_s: number; segments: number } {
  const moves = path.points.map((end) => ({ end }));
  const t0 = performance.now();
  const plan = planPath(path.start, moves, BENCH_LIMITS);
  const seconds = (performance.now() - t0) / 1000;
  return { seconds, plannedDuration_s: plan.duration, segments: plan.segments.length };
}

function median(xs: number[]): number {
  const s = [...xs].sort((a, b) => a - b);
  return s[Math.floor(s.length / 2)];
}

const WARMUP = 2;
const results: Record<string, unknown> = {};
let worst = Infinity;
for (const path of benchPaths()) {
  // Incremental and batch runs are kept apart, so one's garbage does not land in the other's timing.
  const maxl = machineFor(path);
  for (let r = 0; r < WARMUP; r++) await incremental(maxl, path);
  const inc = [];
  for (let r = 0; r < RUNS; r++) inc.push(await incremental(maxl, path));
  for (let r = 0; r < WARMUP; r++) batch(path);
  const bat = [];
  for (let r = 0; r < RUNS; r++) bat.push(batch(path));
  const incRate = median(inc.map((x) => x.segments / x.seconds));
  const batRate = median(bat.map((x) => x.segments / x.seconds));
  worst = Math.min(worst, incRate);
  results[path.name] = {
    describe: path.describe,
    segments: inc[0].segments,
    incremental: { segmentsPerSecond: Math.round(incRate), plannedDuration_s: +inc[0].plannedDuration_s.toFixed(4) },
    planPath: { segmentsPerSecond: Math.round(batRate), plannedDuration_s: +bat[0].plannedDuration_s.toFixed(4) },
  };
  console.error(`${path.name}: incremental ${Math.round(incRate)} seg/s, planPath ${Math.round(batRate)} seg/s`);
}
console.log(
  JSON.stringify({
    bench: 'planner',
    segmentsPerSecond: Math.round(worst),
    target: 1_000_000,
    limits: BENCH_LIMITS,
    runs: RUNS,
    warmupRuns: WARMUP,
    paths: results,
    machine: { cpu: os.cpus()[0]?.model, node: process.version },
  }),
);
