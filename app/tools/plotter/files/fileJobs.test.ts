/**
 * The worker's file module against a real author on the Blot's configuration (no
 * links: the job itself is the workbench's, seen here as what `startJob` is
 * given): what it posts for a file, a bad file and a drawing too large, and the
 * plot time it posts and hands to the job equal to planPath's duration of the
 * very moves it hands over.
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { createMAXL, planPath } from '../../../../core/index.ts';
import { blotPlotter } from '../../../../core/sim/presets/index.ts';
import type { MoveJob } from '../../../worker/jobRunner.ts';
import type { LogLevel, WorkerEvent } from '../../../worker/protocol.ts';
import type { ToolContext } from '../../../worker/toolContext.ts';
import { DEFAULT_ARRANGEMENT } from './arrange.ts';
import { FileJobs } from './fileJobs.ts';
import { pathMoves } from './plotJob.ts';
import type { FileEvent, ImportSettings, PlotSettings } from './protocol.ts';

const config = blotPlotter().config;
const IMPORT: ImportSettings = { chordTolerance_mm: 0.02, gcodePen: 'auto', zThreshold_mm: 0 };
const PLOT: PlotSettings = { arrangement: DEFAULT_ARRANGEMENT, merge: true, mergeTolerance_mm: 0.05, sort: true, drawSpeed: 40, travelSpeed: 120, penDelayDown_s: 0.15, penDelayUp_s: 0.12 };

function setup() {
  const maxl = createMAXL(config, { initialPosition: [7, 3] });
  const posted: FileEvent[] = [];
  const jobs: MoveJob[] = [];
  const logs: Array<{ level: LogLevel; code: string; message: string }> = [];
  const ctx = {
    maxl,
    phase: 'ready',
    sim: null,
    presetId: 'blotPlotter',
    config,
    origin: [0, 0],
    scheduler: maxl.scheduler,
    streamingToBoards: false,
    claim: () => true,
    release: () => {},
    startJob: (job: MoveJob) => {
      jobs.push(job);
      return true;
    },
    log: (level: LogLevel, code: string, message: string) => logs.push({ level, code, message }),
    post: (e: WorkerEvent) => posted.push(e as FileEvent),
  } as unknown as ToolContext;
  const files = new FileJobs(ctx);
  /** As the workbench's: real boards streamed (a job runs on them), or not. */
  const streaming = (on: boolean) => ((ctx as { streamingToBoards: boolean }).streamingToBoards = on);
  const last = <T extends FileEvent['type']>(type: T) => posted.filter((e) => e.type === type).at(-1) as Extract<FileEvent, { type: T }> | undefined;
  return { files, posted, jobs, logs, last, streaming };
}

const svg = readFileSync('e2e/fixtures/plot-shapes.svg', 'utf8');

describe('FileJobs', () => {
  it('loads a file, previews it with its travel and plot time, and plots exactly what it timed', () => {
    const { files, jobs, last } = setup();
    files.handle({ tool: 'plotter', type: 'file-load', name: 'plot-shapes.svg', text: svg, import: IMPORT, plot: PLOT });
    expect(last('file-loaded')?.summary).toMatchObject({ name: 'plot-shapes.svg', kind: 'svg', paths: 4 });
    const preview = last('file-preview')!;
    expect(preview.stats.fits).toBe(true);
    expect(preview.stats.travelAfter_mm).toBeLessThan(preview.stats.travelBefore_mm);
    expect(preview.layer.strokes.ends).toHaveLength(4);
    expect(preview.layer.strokes.ends[3]).toBe(preview.layer.strokes.xy.length / 2);
    expect(preview.layer.travel).toHaveLength(4 * 4);
    // The first travel starts where the pen is.
    expect(Array.from(preview.layer.travel.slice(0, 2))).toEqual([7, 3]);

    files.handle({ tool: 'plotter', type: 'file-plot' });
    expect(jobs).toHaveLength(1);
    const job = jobs[0];
    const t = planPath([7, 3], pathMoves(job.moves, config.motionAxes, [7, 3]), config.limits).duration;
    expect(job.planned_s).toBe(t);
    expect(preview.stats.plotTime_s).toBe(t);
    expect(last('file-plot')).toMatchObject({ started: true, planned_s: t });
  });

  it('while real boards are streamed, a load and a change of settings wait, said, and run once the stream ends', () => {
    const { files, posted, last, streaming } = setup();
    streaming(true);
    files.handle({ tool: 'plotter', type: 'file-load', name: 'plot-shapes.svg', text: svg, import: IMPORT, plot: PLOT });
    files.handle({ tool: 'plotter', type: 'file-settings', import: IMPORT, plot: { ...PLOT, drawSpeed: 20 } });
    // Nothing read or planned on the streaming thread; the page is told why it waits.
    expect(posted.map((e) => e.type)).toEqual(['file-waiting', 'file-waiting']);
    expect(last('file-waiting')).toMatchObject({ name: 'plot-shapes.svg' });
    files.frame();
    expect(last('file-loaded')).toBeUndefined();
    // The stream ends: the next frame reads the file and plans it with the settings given last.
    streaming(false);
    files.frame();
    expect(last('file-loaded')?.summary).toMatchObject({ name: 'plot-shapes.svg', paths: 4 });
    const slow = last('file-preview')!.stats.plotTime_s as number;
    files.handle({ tool: 'plotter', type: 'file-settings', import: IMPORT, plot: { ...PLOT, drawSpeed: 40 } });
    expect(last('file-preview')!.stats.plotTime_s).toBeLessThan(slow);
    files.handle({ tool: 'plotter', type: 'file-settings', import: IMPORT, plot: { ...PLOT, drawSpeed: 20 } });
    expect(last('file-preview')!.stats.plotTime_s).toBe(slow);
    // Cleared while a load waits: nothing runs later.
    streaming(true);
    files.handle({ tool: 'plotter', type: 'file-load', name: 'other.svg', text: svg, import: IMPORT, plot: PLOT });
    files.handle({ tool: 'plotter', type: 'file-clear' });
    streaming(false);
    const before = posted.length;
    files.frame();
    expect(posted.length).toBe(before);
  });

  it('a bad file is refused with its line, and the file before it stays', () => {
    const { files, jobs, last, logs } = setup();
    files.handle({ tool: 'plotter', type: 'file-load', name: 'plot-shapes.svg', text: svg, import: IMPORT, plot: PLOT });
    files.handle({ tool: 'plotter', type: 'file-load', name: 'bad.svg', text: '<svg xmlns="http://www.w3.org/2000/svg">\n<circle r="-1"/></svg>', import: IMPORT, plot: PLOT });
    expect(last('file-error')).toMatchObject({ name: 'bad.svg', line: 2 });
    expect(last('file-error')?.message).toMatch(/“bad.svg” was not loaded: line 2: <circle> has a negative r/);
    expect(logs.at(-1)).toMatchObject({ level: 'error', code: 'FILE_INVALID' });
    files.handle({ tool: 'plotter', type: 'file-plot' });
    expect(jobs[0].name).toBe('plot-shapes.svg');
  });

  it('a drawing larger than the bed is said, not plotted, until it is fitted', () => {
    const { files, jobs, last } = setup();
    const big = { ...PLOT, arrangement: { ...DEFAULT_ARRANGEMENT, scale: 5 } };
    files.handle({ tool: 'plotter', type: 'file-load', name: 'plot-shapes.svg', text: svg, import: IMPORT, plot: big });
    expect(last('file-preview')?.stats.fits).toBe(false);
    expect(last('file-preview')?.stats.notes.join(' ')).toMatch(/leaves the bed's soft limits: fit it.*nothing is clipped/);
    files.handle({ tool: 'plotter', type: 'file-plot' });
    expect(jobs).toHaveLength(0);
    expect(last('file-plot')).toMatchObject({ started: false });
    files.handle({ tool: 'plotter', type: 'file-settings', import: IMPORT, plot: { ...big, arrangement: { ...big.arrangement, fit: true } } });
    expect(last('file-preview')?.stats.fits).toBe(true);
    files.handle({ tool: 'plotter', type: 'file-plot' });
    expect(jobs).toHaveLength(1);
  });

  it('bad settings (a scale of 0, an emptied speed) are said by their field, nothing is planned or plotted, and fixing them plans again', () => {
    const { files, jobs, posted, last } = setup();
    files.handle({ tool: 'plotter', type: 'file-load', name: 'plot-shapes.svg', text: svg, import: IMPORT, plot: PLOT });
    const previews = () => posted.filter((e) => e.type === 'file-preview').length;
    const before = previews();
    // A scale of 0 once collapsed the drawing onto one point, previewed as 0 × 0 mm and plottable.
    files.handle({ tool: 'plotter', type: 'file-settings', import: IMPORT, plot: { ...PLOT, arrangement: { ...DEFAULT_ARRANGEMENT, scale: 0 } } });
    expect(last('file-error')).toMatchObject({ stage: 'plan', name: 'plot-shapes.svg', line: null });
    expect(last('file-error')?.message).toMatch(/^“plot-shapes.svg” cannot be planned: Scale must be a number above 0 .*\(it is 0\)\.$/);
    expect(previews()).toBe(before);
    files.handle({ tool: 'plotter', type: 'file-plot' });
    expect(jobs).toHaveLength(0);
    expect(last('file-plot')).toMatchObject({ started: false });
    expect(last('file-plot')?.reason).toMatch(/Scale must be/);
    // An emptied field arrives as null: once the planner's refusal of "line 12" of the file.
    files.handle({ tool: 'plotter', type: 'file-settings', import: IMPORT, plot: { ...PLOT, drawSpeed: null as unknown as number } });
    expect(last('file-error')?.message).toBe('“plot-shapes.svg” cannot be planned: Pen-down speed must be a speed of at least 0.001 mm/s (it is empty).');
    expect(last('file-error')?.line).toBeNull();
    files.handle({ tool: 'plotter', type: 'file-settings', import: { ...IMPORT, chordTolerance_mm: 0 }, plot: PLOT });
    expect(last('file-error')?.message).toMatch(/Chord tolerance must be a number of mm above 0 \(it is 0\)/);
    expect(previews()).toBe(before);
    files.handle({ tool: 'plotter', type: 'file-plot' });
    expect(jobs).toHaveLength(0);
    // Fixed: planned and plottable again.
    files.handle({ tool: 'plotter', type: 'file-settings', import: IMPORT, plot: PLOT });
    expect(previews()).toBe(before + 1);
    expect(last('file-preview')?.stats.width_mm).toBeGreaterThan(30);
    files.handle({ tool: 'plotter', type: 'file-plot' });
    expect(jobs).toHaveLength(1);
  });

  it('G-code: warnings with their lines in the summary; speeds above the machine’s are said', () => {
    const { files, last } = setup();
    files.handle({ tool: 'plotter', type: 'file-load', name: 'plot-arcs.gcode', text: readFileSync('e2e/fixtures/plot-arcs.gcode', 'utf8'), import: IMPORT, plot: { ...PLOT, drawSpeed: 500 } });
    expect(last('file-loaded')?.warnings.map((w) => w.line)).toEqual([9, 12, 15, 16]);
    expect(last('file-preview')?.stats.notes).toContain("The pen-down speed 500 mm/s is above the machine's 120 mm/s: it runs at 120 mm/s.");
  });

  it('a move the planner refuses is said with the line of the file it comes from, and nothing is plotted', () => {
    const { files, jobs, posted, last, logs } = setup();
    // F0.05 mm/min is 0.00083 mm/s: the import takes any F > 0, the planner no speed below 0.001 mm/s.
    const text = 'M3\nG1 X10 Y10 F600\nG1 X20 F0.05\nG1 Y20\nM5\n';
    files.handle({ tool: 'plotter', type: 'file-load', name: 'slow.gcode', text, import: IMPORT, plot: PLOT });
    const error = last('file-error');
    expect(error).toMatchObject({ name: 'slow.gcode', line: 3 });
    expect(error?.message).toMatch(/^“slow.gcode” cannot be plotted: line 3 \(move \d+ of the job\): maxVelocity: must be at least 0.001 mm\/s, got 0.000833/);
    expect(logs.at(-1)).toMatchObject({ level: 'error', code: 'FILE_INVALID', message: error?.message });
    expect(posted.some((e) => e.type === 'file-preview')).toBe(false);
    files.handle({ tool: 'plotter', type: 'file-plot' });
    expect(jobs).toHaveLength(0);
  });

  it('the job it hands over says where each move comes from: the G-code line, or the SVG element’s', () => {
    const { files, jobs } = setup();
    files.handle({ tool: 'plotter', type: 'file-load', name: 'square.gcode', text: 'M3\nG1 X10 Y10 F600\nG1 X20\nG1 Y20\nM5\n', import: IMPORT, plot: PLOT });
    files.handle({ tool: 'plotter', type: 'file-plot' });
    const job = jobs[0];
    const where = job.moves.map((_, i) => job.describeMove?.(i));
    expect(where[0]).toBe('the pen lift before the plot');
    expect(new Set(where.slice(1))).toEqual(new Set(['line 2', 'line 3', 'line 4']));

    files.handle({ tool: 'plotter', type: 'file-load', name: 'plot-shapes.svg', text: svg, import: IMPORT, plot: PLOT });
    files.handle({ tool: 'plotter', type: 'file-plot' });
    const svgJob = jobs[1];
    const svgLines = new Set(svgJob.moves.slice(1).map((_, i) => svgJob.describeMove?.(i + 1)));
    // One line per drawn element of the fixture, each a line of the file.
    expect(svgLines.size).toBe(4);
    for (const w of svgLines) expect(w).toMatch(/^line \d+$/);
  });
});
