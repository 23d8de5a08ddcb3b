/**
 * `npm run bench -- plotfiles`: the plotter's file path on its fixtures and on a
 * scattered drawing, on the Blot preset (soft limits 0–125 mm, 120 mm/s,
 * 1 500 mm/s²), the pen starting at (0, 0), pen-down 40 mm/s, travel 120 mm/s; placed
 * as the panel places a new file (an SVG true size and centred, G-code at its own
 * coordinates from the origin).
 *
 * Figures, per drawing (named in the JSON):
 * - travelFileOrder_mm: pen-up travel from (0, 0) through the paths in the file's order;
 * - travelPlanned_mm: the same after linemerge (0.05 mm) and linesort (ordering.ts);
 * - plotTime_s: planPath's duration of the job's moves, with no link floor;
 * - plotTimeOnLink_s (fixtures only): the same with the simulated link's floor on segment
 *   durations (linkFloor_us, maxl.feedLimit): what the panel shows on that machine;
 * - queuePlan_s: the queue's own plan of the same moves (all appended, planned to rest);
 * - simRun_s (fixtures only): first segment's start to last segment's end as transmitted
 *   to the simulated Blot (real firmware in wasm, virtual time);
 * - inkHausdorff_mm (fixtures only): Hausdorff distance between the simulated ink and
 *   the placed source (target ≤ chord tolerance 0.02 + 0.1 mm).
 * The scattered drawing: 400 strokes of 1–6 mm at seeded random places and angles in
 * 100 × 100 mm (mulberry32, seed 7), a hard case for ordering.
 */
import { readFileSync } from 'node:fs';
import { createMAXL, type Move } from '../core/index.ts';
import { blotPlotter } from '../core/sim/presets/index.ts';
import { runJob, startMachine } from '../core/system/harness.ts';
import type { SegmentView } from '../core/index.ts';
import type { PenSettings } from '../app/tools/plotter/penSequence.ts';
import { arrange, DEFAULT_ARRANGEMENT, type Arrangement } from '../app/tools/plotter/files/arrange.ts';
import { importGcode } from '../app/tools/plotter/files/gcodeImport.ts';
import { hausdorff } from '../app/tools/plotter/geometry/hausdorff.ts';
import { mergePaths, sortPaths } from '../app/tools/plotter/files/ordering.ts';
import { pathFromPoints, travelLength, type PlotPath } from '../app/tools/plotter/files/paths.ts';
import { plotJobMoves, plotTime } from '../app/tools/plotter/files/plotJob.ts';
import { importSvg } from '../app/tools/plotter/files/svgImport.ts';
import { queueOf } from '../core/maxl.ts';

const preset = blotPlotter();
const BED = { minX: 0, minY: 0, maxX: 125, maxY: 125 };
const pen: PenSettings = { channel: 'pen', up: 0, down: 1, delayDown_s: 0.15, delayUp_s: 0.12, drawSpeed: 40, travelSpeed: 120, axes: ['x', 'y'] };
const START: [number, number] = [0, 0];

function queuePlan(moves: readonly Move[]): number {
  const maxl = createMAXL({ ...preset.config, queueCapacity: moves.length + 10 });
  for (const m of moves) queueOf(maxl).append(m);
  queueOf(maxl).planToRest();
  return queueOf(maxl).segments().reduce((t, s) => t + s.duration_s, 0);
}

async function simulate(moves: Move[], source: PlotPath[]): Promise<{ simRun_s: number; inkHausdorff_mm: number; plotTimeOnLink_s: number; minSegment_us: number }> {
  const b = await startMachine(preset, { sim: { outputLogSize: 200_000 } });
  const minSegment_us = b.maxl.feedLimit?.minSegment_us ?? 0;
  const plotTimeOnLink_s = plotTime(moves, preset.config.motionAxes, [...START], preset.config.limits, minSegment_us);
  const sent: SegmentView[] = [];
  b.maxl.queue.subscribe((e) => {
    if (e.type === 'transmitted') sent.push(...e.segments);
  });
  await runJob(b, moves);
  const ink = (b.sim.plant.pen?.strokes ?? []).map((s) => Float64Array.from(s.x.flatMap((x, i) => [x, s.y[i]])));
  return {
    plotTimeOnLink_s,
    minSegment_us,
    simRun_s: (sent[sent.length - 1].endTime_us - sent[0].startTime_us) * 1e-6,
    inkHausdorff_mm: hausdorff(
      ink,
      source.map((p) => p.points),
      0.01,
    ),
  };
}

async function measure(paths: PlotPath[], run: boolean, arrangement: Arrangement = DEFAULT_ARRANGEMENT) {
  const placed = arrange(paths, arrangement, BED, [0, 0]).paths;
  const ordered = sortPaths(mergePaths(placed, 0.05), START);
  const moves = plotJobMoves(ordered, pen);
  const out: Record<string, number> = {
    paths: placed.length,
    travelFileOrder_mm: round(travelLength(placed, START), 1),
    travelPlanned_mm: round(travelLength(ordered, START), 1),
    plotTime_s: round(plotTime(moves, preset.config.motionAxes, [...START], preset.config.limits, 0), 4),
    queuePlan_s: round(queuePlan(moves), 4),
  };
  if (run) {
    const sim = await simulate(moves, placed);
    out.plotTimeOnLink_s = round(sim.plotTimeOnLink_s, 4);
    out.linkFloor_us = round(sim.minSegment_us, 1);
    out.simRun_s = round(sim.simRun_s, 4);
    out.inkHausdorff_mm = round(sim.inkHausdorff_mm, 4);
  }
  return out;
}

function round(v: number, digits: number): number {
  const f = 10 ** digits;
  return Math.round(v * f) / f;
}

function mulberry32(seed: number): () => number {
  let a = seed;
  return () => {
    a = (a + 0x6d2b79f5) | 0;
    let t = Math.imul(a ^ (a >>> 15), 1 | a);
    t = (t + Math.imul(t ^ (t >>> 7), 61 | t)) ^ t;
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

function scattered(): PlotPath[] {
  const rnd = mulberry32(7);
  const out: PlotPath[] = [];
  for (let i = 0; i < 400; i++) {
    const x = rnd() * 100, y = rnd() * 100, a = rnd() * 2 * Math.PI, l = 1 + 5 * rnd();
    out.push(pathFromPoints([x, y, x + l * Math.cos(a), y + l * Math.sin(a)]));
  }
  return out;
}

const svg = importSvg('plot-shapes.svg', readFileSync('e2e/fixtures/plot-shapes.svg', 'utf8'));
const gcode = importGcode('plot-arcs.gcode', readFileSync('e2e/fixtures/plot-arcs.gcode', 'utf8'), { maxSpeed_mm_s: 120 });
const result = {
  svgFixture: await measure(svg.paths, true),
  gcodeFixture: await measure(gcode.paths, true, { ...DEFAULT_ARRANGEMENT, place: 'file' }),
  scattered400: await measure(scattered(), false),
};
console.log(JSON.stringify(result));
