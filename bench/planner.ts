/**
 * npm run bench -- planner
 *
 * Plans four 100 000-segment paths (bench/paths.ts: a fine spiral, a raster, a random
 * walk and a finely flattened circle of 3 µm chords) two ways, at the default
 * settings (queue capacity and all):
 *  - incremental: through the queue, one awaited addSegmentToQueue per point (the
 *    paper's Listing 2), drained by a DryRun (core/trajectory/dryRun.ts), an executor
 *    with no device that takes a segment whenever the queue has no room, then the
 *    rest at the end; one MAXL per path, kept across runs as a workbench keeps it
 *    across jobs;
 *  - batch: planPath over the whole path.
 *
 * Figures, per path:
 *  - segmentsPerSecond: segments planned (and, incrementally, locked and retired) per
 *    second of wall time, the median over RUNS timed runs after WARMUP runs;
 *  - coldSegmentsPerSecond: the same for the very first run on that path (a fresh
 *    MAXL, code not yet optimised for its data), not part of the median;
 *  - cpuSegmentsPerSecond: segments per second of this process's CPU time (user +
 *    system, all its threads: the garbage collector's too), the median over the
 *    same runs. On a busy machine (the bench shares two cores with other work) the
 *    wall-time figure falls with the load; this one counts only the time the
 *    process ran, so it compares trees measured at different loads better. The
 *    targets are set on the wall-time figure of a quiet run;
 *  - plannedDuration_s: the duration of the plan, s (the sum of the segments' durations);
 *  - durationRatio: incremental plannedDuration_s / planPath's (1 = the queue's
 *    lookahead found the time-optimal plan).
 * Top level: segmentsPerSecond, coldSegmentsPerSecond and cpuSegmentsPerSecond are
 * the worst path's incremental rates; worstDurationRatio the largest durationRatio;
 * worstPlanPathSpeedup the smallest planPath rate / incremental rate.
 *
 * Options: `--path NAME[,NAME…]` plans only the paths named (spiral, raster,
 * randomWalk, fineCircle), for profiling one path or comparing two trees quickly;
 * BENCH_RUNS (default 5) sets the timed runs per path.
 */
import os from 'node:os';
import { createMAXL, planPath } from '../core/index.ts';
import { queueOf } from '../core/maxl.ts';
import { DryRun } from '../core/trajectory/dryRun.ts';
import { benchPaths, fineCircle, BENCH_LIMITS, type BenchPath } from './paths.ts';

const RUNS = Number(process.env.BENCH_RUNS ?? 5);
const WARMUP = 2;

/** The paths to plan: all four, or those named by `--path a,b`. */
function selectedPaths(): BenchPath[] {
  const all = [...benchPaths(), fineCircle()];
  const at = process.argv.indexOf('--path');
  if (at < 0) return all;
  const names = (process.argv[at + 1] ?? '').split(',').filter((n) => n !== '');
  const unknown = names.filter((n) => !all.some((p) => p.name === n));
  if (names.length === 0 || unknown.length > 0) {
    console.error(`--path: unknown path ${unknown.join(', ') || '(none given)'}; the paths are ${all.map((p) => p.name).join(', ')}`);
    process.exit(2);
  }
  return all.filter((p) => names.includes(p.name));
}

interface Run {
  seconds: number;
  /** s of the process's CPU time (user + system) during the run. */
  cpuSeconds: number;
  plannedDuration_s: number;
  segments: number;
}

/**
 * One machine per path, reused for every run, as a workbench keeps one MAXL across
 * jobs: its history ring is allocated and paged in once (the warm-up runs), so the
 * timed runs measure planning, not first-touch page faults. Each run starts the
 * path again from where the last ended (at rest).
 */
function machineFor(path: BenchPath) {
  return createMAXL({ motionAxes: ['x', 'y'], limits: BENCH_LIMITS }, { initialPosition: path.start });
}

async function incremental(maxl: ReturnType<typeof machineFor>, path: BenchPath): Promise<Run> {
  // Back to the start first (one move), so every run plans the same path from rest.
  await maxl.addSegmentToQueue({ endPosition: path.start });
  new DryRun(queueOf(maxl)).finish();
  const dry = new DryRun(queueOf(maxl));
  const c0 = process.cpuUsage();
  const t0 = performance.now();
  for (const p of path.points) {
    await maxl.addSegmentToQueue({ endPosition: p });
    dry.takeWhileFull();
  }
  dry.finish();
  const seconds = (performance.now() - t0) / 1000;
  return { seconds, cpuSeconds: cpuSecondsSince(c0), plannedDuration_s: dry.duration_s, segments: dry.segments };
}

function batch(path: BenchPath): Run {
  const moves = path.points.map((end) => ({ end }));
  const c0 = process.cpuUsage();
  const t0 = performance.now();
  const plan = planPath(path.start, moves, BENCH_LIMITS);
  const seconds = (performance.now() - t0) / 1000;
  return { seconds, cpuSeconds: cpuSecondsSince(c0), plannedDuration_s: plan.duration, segments: plan.segmentCount };
}

function cpuSecondsSince(start: NodeJS.CpuUsage): number {
  const d = process.cpuUsage(start);
  return (d.user + d.system) / 1e6;
}

function median(xs: number[]): number {
  const s = [...xs].sort((a, b) => a - b);
  return s[Math.floor(s.length / 2)];
}

const rate = (r: Run) => r.segments / r.seconds;
const cpuRate = (r: Run) => r.segments / r.cpuSeconds;

const results: Record<string, unknown> = {};
let worst = Infinity;
let worstCold = Infinity;
let worstCpu = Infinity;
let worstDurationRatio = 0;
let worstPlanPathSpeedup = Infinity;
for (const path of selectedPaths()) {
  // Incremental and batch runs are kept apart, so one's garbage does not land in the other's timing.
  const maxl = machineFor(path);
  const incCold = await incremental(maxl, path);
  for (let r = 1; r < WARMUP; r++) await incremental(maxl, path);
  const inc: Run[] = [];
  for (let r = 0; r < RUNS; r++) inc.push(await incremental(maxl, path));
  const batCold = batch(path);
  for (let r = 1; r < WARMUP; r++) batch(path);
  const bat: Run[] = [];
  for (let r = 0; r < RUNS; r++) bat.push(batch(path));
  const incRate = median(inc.map(rate));
  const batRate = median(bat.map(rate));
  const incCpuRate = median(inc.map(cpuRate));
  const durationRatio = inc[0].plannedDuration_s / bat[0].plannedDuration_s;
  worst = Math.min(worst, incRate);
  worstCold = Math.min(worstCold, rate(incCold));
  worstCpu = Math.min(worstCpu, incCpuRate);
  worstDurationRatio = Math.max(worstDurationRatio, durationRatio);
  worstPlanPathSpeedup = Math.min(worstPlanPathSpeedup, batRate / incRate);
  results[path.name] = {
    describe: path.describe,
    segments: inc[0].segments,
    incremental: {
      segmentsPerSecond: Math.round(incRate),
      coldSegmentsPerSecond: Math.round(rate(incCold)),
      cpuSegmentsPerSecond: Math.round(incCpuRate),
      plannedDuration_s: +inc[0].plannedDuration_s.toFixed(4),
    },
    planPath: {
      segmentsPerSecond: Math.round(batRate),
      coldSegmentsPerSecond: Math.round(rate(batCold)),
      cpuSegmentsPerSecond: Math.round(median(bat.map(cpuRate))),
      plannedDuration_s: +bat[0].plannedDuration_s.toFixed(4),
    },
    durationRatio: +durationRatio.toFixed(7),
  };
  console.error(`${path.name}: incremental ${Math.round(incRate)} seg/s (cold ${Math.round(rate(incCold))}, per CPU second ${Math.round(incCpuRate)}), planPath ${Math.round(batRate)} seg/s, duration ratio ${durationRatio.toFixed(7)}`);
}
console.log(
  JSON.stringify({
    bench: 'planner',
    segmentsPerSecond: Math.round(worst),
    coldSegmentsPerSecond: Math.round(worstCold),
    cpuSegmentsPerSecond: Math.round(worstCpu),
    target: 3_000_000,
    worstDurationRatio: +worstDurationRatio.toFixed(7),
    durationRatioTarget: 1.000001,
    worstPlanPathSpeedup: +worstPlanPathSpeedup.toFixed(3),
    limits: BENCH_LIMITS,
    runs: RUNS,
    warmupRuns: WARMUP,
    paths: results,
    machine: { cpu: os.cpus()[0]?.model, node: process.version, loadAverage1m: +os.loadavg()[0].toFixed(2) },
  }),
);
