/**
 * The whole file path on the simulated Blot plotter (the real BlotPlotter firmware
 * in wasm, the plant's pen servo), in virtual time: the e2e fixtures imported,
 * placed, merged and sorted, run as the job's moves; then
 * - the simulated ink matches the source, placed the same way, within the chord
 *   tolerance + 0.1 mm (Hausdorff, both ways: no ink on travel, nothing missing);
 * - the plot time shown before plotting is the run's duration (first segment's
 *   start to last segment's end, as transmitted).
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { blotPlotter } from '../../../../core/sim/presets/index.ts';
import { runJob, startMachine } from '../../../../core/system/harness.ts';
import type { SegmentView } from '../../../../core/index.ts';
import type { PenSettings } from '../penSequence.ts';
import { arrange, DEFAULT_ARRANGEMENT, type Arrangement } from './arrange.ts';
import { DEFAULT_CHORD_TOLERANCE_MM } from './flatten.ts';
import { importGcode } from './gcodeImport.ts';
import { hausdorff } from '../geometry/hausdorff.ts';
import { mergePaths, sortPaths } from './ordering.ts';
import type { Drawing } from './paths.ts';
import { plotJobMoves, plotTime } from './plotJob.ts';
import { importSvg } from './svgImport.ts';

const pen: PenSettings = { channel: 'pen', up: 0, down: 1, delayDown_s: 0.15, delayUp_s: 0.12, drawSpeed: 40, travelSpeed: 120, axes: ['x', 'y'] };
const BED = { minX: 0, minY: 0, maxX: 125, maxY: 125 };

async function plot(drawing: Drawing, arrangement: Arrangement) {
  const preset = blotPlotter();
  const b = await startMachine(preset, { sim: { outputLogSize: 200_000 } });
  const start = [...b.maxl.nextMoveStart];
  const source = arrange(drawing.paths, arrangement, BED, [0, 0]).paths;
  const ordered = sortPaths(mergePaths(source, 0.05), [start[0], start[1]]);
  const moves = plotJobMoves(ordered, pen);
  const planned_s = plotTime(moves, preset.config.motionAxes, start, preset.config.limits, b.maxl.feedLimit?.minSegment_us ?? 0);
  const sent: SegmentView[] = [];
  b.maxl.queue.subscribe((e) => {
    if (e.type === 'transmitted') sent.push(...e.segments);
  });
  await runJob(b, moves);
  const ink = (b.sim.plant.pen?.strokes ?? []).map((s) => Float64Array.from(s.x.flatMap((x, i) => [x, s.y[i]])));
  const ran_s = (sent[sent.length - 1].endTime_us - sent[0].startTime_us) * 1e-6;
  return { source: source.map((p) => p.points), ink, planned_s, ran_s, strokes: ordered.length };
}

describe('files plotted on the simulated Blot', () => {
  it('the SVG fixture: ink within the chord tolerance + 0.1 mm of the source; the plot time is the run’s', async () => {
    const drawing = importSvg('plot-shapes.svg', readFileSync('e2e/fixtures/plot-shapes.svg', 'utf8'));
    const r = await plot(drawing, DEFAULT_ARRANGEMENT);
    expect(r.ink.length).toBe(r.strokes);
    const h = hausdorff(r.ink, r.source, 0.01);
    console.log(`[plotOnBlot] SVG: Hausdorff(ink, source) ${h.toFixed(4)} mm; plot time ${r.planned_s.toFixed(4)} s planned, ${r.ran_s.toFixed(4)} s run`);
    expect(h).toBeLessThanOrEqual(DEFAULT_CHORD_TOLERANCE_MM + 0.1);
    expect(Math.abs(r.ran_s - r.planned_s)).toBeLessThan(1e-6 * r.planned_s + 1e-6);
  }, 120_000);

  it('the G-code fixture, rotated a quarter turn: the same', async () => {
    const drawing = importGcode('plot-arcs.gcode', readFileSync('e2e/fixtures/plot-arcs.gcode', 'utf8'), { maxSpeed_mm_s: 120 });
    const r = await plot(drawing, { ...DEFAULT_ARRANGEMENT, rotate_deg: 90 });
    const h = hausdorff(r.ink, r.source, 0.01);
    console.log(`[plotOnBlot] G-code: Hausdorff(ink, source) ${h.toFixed(4)} mm; plot time ${r.planned_s.toFixed(4)} s planned, ${r.ran_s.toFixed(4)} s run`);
    expect(h).toBeLessThanOrEqual(DEFAULT_CHORD_TOLERANCE_MM + 0.1);
    expect(Math.abs(r.ran_s - r.planned_s)).toBeLessThan(1e-6 * r.planned_s + 1e-6);
  }, 120_000);
});
