/**
 * npm run bench -- planner
 *
 * Plans four 100 000-segment paths (bench/paths.ts: a fine spiral, a raster, a random
 * walk and a finely flattened circle of 3 µm chords) three ways, at the default
 * settings (queue capacity and all):
 *  - incremental, per point: through the queue, one awaited addSegmentToQueue per
 *    point (the paper's Listing 2), drained by a DryRun (core/trajectory/dryRun.ts),
 *    an executor with no device; one MAXL per path, kept across runs as a workbench
 *    keeps it across jobs;
 *  - incremental, batch: the same queue and plan, fed by the batch API
 *    (maxl.addSegmentsNow(moves, from): appends synchronously while there is room,
 *    no promise per point) from the moves made once before the runs, as planPath's
 *    are;
 *    both incremental ways have the same executor, so that they differ only in the
 *    producer's API: after each add (per point) or run of adds (batch) the dry run
 *    checks for room, and once the queue has none it takes final segments until
 *    there is room for a run of EXECUTOR_RUN (takeWhileFull(EXECUTOR_RUN)), as the
 *    device streamer (core/net/streamer.ts) tops a board's buffer up by a refill's
 *    worth of path, not one segment per tick; then the rest at the end. Locking a
 *    final segment changes no plan (core/trajectory/batchAppend.property.test.ts),
 *    and durationRatio checks both plans against planPath's. (A dry run taking one
 *    segment after each add, as this bench's per-point loop had before, makes
 *    producer and executor alternate per point: the same plan, more time per point;
 *    README, "planner".)
 *  - batch: planPath over the whole path.
 *
 * Figures, per path and per way (incremental = per point, incrementalBatch, planPath):
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
 *  - durationRatio: the larger of the two incremental plannedDuration_s over
 *    planPath's (1 = the queue's lookahead found the time-optimal plan).
 * Top level (`api` names the call each is of):
 *  - segmentsPerSecond, coldSegmentsPerSecond, cpuSegmentsPerSecond: the worst path's
 *    incremental rates through the batch API (addSegmentsNow);
 *  - perPoint: the same three through the awaited per-point addSegmentToQueue;
 *  - worstDurationRatio: the largest durationRatio;
 *  - worstPlanPathSpeedup: the smallest, over paths, of planPath's rate over the
 *    faster incremental rate (the batch API's);
 *  - perPoint.ceilingSegmentsPerSecond: the smallest, over paths, of
 *    perPointCeiling.segmentsPerSecond, which is 1 / (1 / loopOnly + 1 / batch):
 *    the per-point rate if an awaited add cost no more than the batch API's whole
 *    cost per segment. loopOnlySegmentsPerSecond is the rate of the per-point loop
 *    itself, with the add replaced by one that only answers (answerOnly: a resolved
 *    promise of a fresh receipt, no queue): the same for…of, move object, await and
 *    executor call (takeWhileFull, on a queue with nothing in it), the median over
 *    the same runs. A per-point API that did the batch API's work per point and
 *    nothing more would run at the ceiling: the per-point rate cannot pass it unless
 *    the queue itself gets faster.
 *
 * Options: `--path NAME[,NAME…]` plans only the paths named (spiral, raster,
 * randomWalk, fineCircle), for profiling one path or comparing two trees quickly;
 * BENCH_RUNS (default 5) sets the timed runs per path.
 */
import os from 'node:os';
import { createMAXL, planPath, type Move, type MoveReceipt } from '../core/index.ts';
import { queueOf } from '../core/maxl.ts';
import { DryRun } from '../core/trajectory/dryRun.ts';
import { benchPaths, fineCircle, BENCH_LIMITS, type BenchPath } from './paths.ts';

const RUNS = Number(process.env.BENCH_RUNS ?? 5);
const WARMUP = 2;
/** Segments of room the dry run makes at a time, once it must take (see the header). */
const EXECUTOR_RUN = 64;

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
    dry.takeWhileFull(EXECUTOR_RUN);
  }
  dry.finish();
  const seconds = (performance.now() - t0) / 1000;
  return { seconds, cpuSeconds: cpuSecondsSince(c0), plannedDuration_s: dry.duration_s, segments: dry.segments };
}

/** The incremental plan through the batch API: runs of moves appended while there is room. */
function incrementalBatch(maxl: ReturnType<typeof machineFor>, path: BenchPath, moves: readonly Move[]): Run {
  maxl.addSegmentsNow([{ endPosition: path.start }]);
  new DryRun(queueOf(maxl)).finish();
  const dry = new DryRun(queueOf(maxl));
  const c0 = process.cpuUsage();
  const t0 = performance.now();
  let next = 0;
  while (next < moves.length) {
    next = maxl.addSegmentsNow(moves, next);
    dry.takeWhileFull(EXECUTOR_RUN);
  }
  dry.finish();
  const seconds = (performance.now() - t0) / 1000;
  return { seconds, cpuSeconds: cpuSecondsSince(c0), plannedDuration_s: dry.duration_s, segments: dry.segments };
}

/** An add that only answers: a resolved promise of a fresh receipt, with no queue behind it (it reads the move, so the caller makes one as for a real add). */
function answerOnly(move: Move, moveId: number): Promise<MoveReceipt> {
  return Promise.resolve({ moveId, segmentIds: [moveId], skipped: 'dwell_s' in move });
}

/**
 * The per-point loop (incremental() above) with its add replaced by answerOnly and
 * its executor's queue empty (`idle`: takeWhileFull returns at its room check, as it
 * does after most adds): what the loop itself costs a point. Nothing is planned;
 * only its rate is used, for the per-point ceiling.
 */
async function loopOnly(path: BenchPath, idle: DryRun): Promise<Run> {
  const c0 = process.cpuUsage();
  const t0 = performance.now();
  let moveId = 0;
  for (const p of path.points) {
    await answerOnly({ endPosition: p }, moveId++);
    idle.takeWhileFull(EXECUTOR_RUN);
  }
  const seconds = (performance.now() - t0) / 1000;
  return { seconds, cpuSeconds: cpuSecondsSince(c0), plannedDuration_s: 0, segments: path.points.length };
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

/** A way of planning measured on one path: its cold run, then its timed runs. */
interface Measured {
  cold: Run;
  runs: Run[];
}

/** Runs `once` WARMUP times (the first is the cold run), then RUNS timed times. */
async function measure(once: () => Run | Promise<Run>): Promise<Measured> {
  const cold = await once();
  for (let r = 1; r < WARMUP; r++) await once();
  const runs: Run[] = [];
  for (let r = 0; r < RUNS; r++) runs.push(await once());
  return { cold, runs };
}

function figures(m: Measured) {
  return {
    segmentsPerSecond: Math.round(median(m.runs.map(rate))),
    coldSegmentsPerSecond: Math.round(rate(m.cold)),
    cpuSegmentsPerSecond: Math.round(median(m.runs.map(cpuRate))),
    plannedDuration_s: +m.runs[0].plannedDuration_s.toFixed(4),
  };
}

type Figures = ReturnType<typeof figures>;

/** The worst (smallest) of each rate over the paths. */
function worstOf(all: Figures[]) {
  return {
    segmentsPerSecond: Math.min(...all.map((f) => f.segmentsPerSecond)),
    coldSegmentsPerSecond: Math.min(...all.map((f) => f.coldSegmentsPerSecond)),
    cpuSegmentsPerSecond: Math.min(...all.map((f) => f.cpuSegmentsPerSecond)),
  };
}

const results: Record<string, unknown> = {};
const perPointFigures: Figures[] = [];
const batchFigures: Figures[] = [];
const ceilings: number[] = [];
let worstDurationRatio = 0;
let worstPlanPathSpeedup = Infinity;
for (const path of selectedPaths()) {
  // Each way's runs are kept apart, so one's garbage does not land in another's timing.
  const perPointMaxl = machineFor(path);
  const perPoint = await measure(() => incremental(perPointMaxl, path));
  const batchMaxl = machineFor(path);
  const moves: Move[] = path.points.map((p) => ({ endPosition: p }));
  const inBatch = await measure(() => incrementalBatch(batchMaxl, path, moves));
  const plan = await measure(() => batch(path));
  const idle = new DryRun(queueOf(machineFor(path)));
  const loop = await measure(() => loopOnly(path, idle));
  const [p, b, pp] = [figures(perPoint), figures(inBatch), figures(plan)];
  const loopOnlyRate = median(loop.runs.map(rate));
  const ceiling = Math.round(1 / (1 / loopOnlyRate + 1 / b.segmentsPerSecond));
  perPointFigures.push(p);
  ceilings.push(ceiling);
  batchFigures.push(b);
  const planned = plan.runs[0].plannedDuration_s;
  const durationRatio = Math.max(perPoint.runs[0].plannedDuration_s, inBatch.runs[0].plannedDuration_s) / planned;
  const fastest = Math.max(p.segmentsPerSecond, b.segmentsPerSecond);
  worstDurationRatio = Math.max(worstDurationRatio, durationRatio);
  worstPlanPathSpeedup = Math.min(worstPlanPathSpeedup, pp.segmentsPerSecond / fastest);
  results[path.name] = {
    describe: path.describe,
    segments: perPoint.runs[0].segments,
    incremental: p,
    incrementalBatch: b,
    perPointCeiling: { loopOnlySegmentsPerSecond: Math.round(loopOnlyRate), segmentsPerSecond: ceiling },
    planPath: pp,
    durationRatio: +durationRatio.toFixed(7),
  };
  console.error(
    `${path.name}: incremental per point ${p.segmentsPerSecond} seg/s (cold ${p.coldSegmentsPerSecond}, per CPU second ${p.cpuSegmentsPerSecond}), ` +
      `batch ${b.segmentsPerSecond} seg/s (cold ${b.coldSegmentsPerSecond}, per CPU second ${b.cpuSegmentsPerSecond}), ` +
      `planPath ${pp.segmentsPerSecond} seg/s, duration ratio ${durationRatio.toFixed(7)}; ` +
      `the loop alone ${Math.round(loopOnlyRate)} per s, per-point ceiling ${ceiling} seg/s`,
  );
}
const worstBatch = worstOf(batchFigures);
console.log(
  JSON.stringify({
    bench: 'planner',
    api: {
      top: 'maxl.addSegmentsNow(moves, from), runs while there is room (the batch API)',
      perPoint: 'await maxl.addSegmentToQueue(move), one per point',
    },
    ...worstBatch,
    perPoint: { ...worstOf(perPointFigures), ceilingSegmentsPerSecond: Math.min(...ceilings) },
    target: 3_000_000,
    worstDurationRatio: +worstDurationRatio.toFixed(7),
    durationRatioTarget: 1.000001,
    worstPlanPathSpeedup: +worstPlanPathSpeedup.toFixed(3),
    limits: BENCH_LIMITS,
    runs: RUNS,
    warmupRuns: WARMUP,
    executorRun: EXECUTOR_RUN,
    paths: results,
    machine: { cpu: os.cpus()[0]?.model, node: process.version, loadAverage1m: +os.loadavg()[0].toFixed(2) },
  }),
);
