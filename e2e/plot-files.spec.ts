/**
 * Plotting files on the simulated Blot plotter:
 * - an SVG with a transformed group, a circle, a cubic Bézier and an arc: preview
 *   (travel before and after ordering, the exact plot time), plot to completion,
 *   then the as-drawn SVG (the simulated pen's ink) matches the source geometry,
 *   placed the same way, within the chord tolerance + 0.1 mm (Hausdorff);
 * - a G-code file with G2/G3 and words the importer does not read: each is listed
 *   with its line number, and the plot completes;
 * - a malformed SVG is refused, naming the line, and the file before it stays;
 * - a G-code move the planner refuses (an F too slow) is said with its line, not plotted;
 * - a setting emptied or set to 0 (scale, pen-down speed) is said by its field, with no
 *   plot time left standing and Plot disabled until it is fixed;
 * - a file of 20 000 paths: said while read and planned, previewed on one canvas (it
 *   was 20 000 SVG elements, the page frozen 1.3-2 s at each plan), and the plot runs;
 * - a G-code file with the pen Z0 down, Z5 up: refused with its heights, the Z threshold
 *   set with no file loaded, and it loads.
 */
import { readFileSync } from 'node:fs';
import type { Page } from '@playwright/test';
import { expect, test } from './support/test.ts';
import { arrange, DEFAULT_ARRANGEMENT } from '../app/tools/plotter/files/arrange.ts';
import { DEFAULT_CHORD_TOLERANCE_MM } from '../app/tools/plotter/files/flatten.ts';
import { hausdorff } from '../app/tools/plotter/geometry/hausdorff.ts';
import { importSvg } from '../app/tools/plotter/files/svgImport.ts';
import { dataNumber, openWorkbench, screenshot, snapshotsPass, usePreset } from './support/workbench.ts';

const SVG_FIXTURE = 'e2e/fixtures/plot-shapes.svg';
const GCODE_FIXTURE = 'e2e/fixtures/plot-arcs.gcode';
/** The Blot preset's soft limits, mm. */
const BED = { minX: 0, minY: 0, maxX: 125, maxY: 125 };

async function useBlot(page: Page): Promise<void> {
  await openWorkbench(page);
  await usePreset(page, 'blotPlotter');
}

async function plotToCompletion(page: Page): Promise<{ elapsed_s: number }> {
  await page.getByTestId('file-plot').click();
  const progress = page.getByTestId('job-progress');
  await expect(progress).toHaveAttribute('data-phase', 'running');
  await expect(progress).toHaveAttribute('data-phase', 'done', { timeout: 60_000 });
  const job = await page.evaluate(() => (window as unknown as { maxlWorkbench: { job: { elapsed_s: number } | null } }).maxlWorkbench.job);
  return { elapsed_s: job?.elapsed_s ?? NaN };
}

/** The polylines of an SVG that the plotter saved: machine mm, x right, y down (its `points` are machine coordinates). */
function savedPolylines(svg: string): Float64Array[] {
  return [...svg.matchAll(/<polyline points="([^"]*)"/g)].map((m) => Float64Array.from(m[1].trim().split(/[\s,]+/).map(Number)));
}

test('an SVG: preview, exact plot time, plot, and the ink matches the file', async ({ page }) => {
  await useBlot(page);
  await page.getByTestId('tab-plot-files').click();
  await page.getByTestId('plot-file-input').setInputFiles(SVG_FIXTURE);

  const summary = page.getByTestId('file-summary');
  await expect(summary).toHaveAttribute('data-kind', 'svg');
  // The rounded rect, the circle, the cubic and the arc; not the circle in <defs>.
  await expect(summary).toHaveAttribute('data-paths', '4');
  await expect(page.getByTestId('file-warnings')).toHaveCount(0);
  await expect(page.getByTestId('plot-time')).toHaveAttribute('data-value', /^\d/);
  const planned = await dataNumber(page, 'plot-time');
  const before = await dataNumber(page, 'travel-before');
  const after = await dataNumber(page, 'travel-after');
  console.log(`[plot-files] SVG: travel ${before.toFixed(1)} mm in the file's order, ${after.toFixed(1)} mm as planned; plot time ${planned.toFixed(3)} s`);
  // The fixture's order sends the pen back and forth; sorting cuts that.
  expect(after).toBeLessThan(before);
  await page.getByTestId('file-show-before').check();
  await screenshot(page, 'plot-files-svg-preview');

  const { elapsed_s } = await plotToCompletion(page);
  console.log(`[plot-files] SVG: ran ${elapsed_s.toFixed(3)} s of motion against ${planned.toFixed(3)} s planned`);
  // The ETA's basis is the plan; the run is the same moves through the bounded queue.
  expect(Math.abs(elapsed_s - planned)).toBeLessThan(0.02 * planned);
  await expect(page.locator('[data-testid=log-entry][data-code=DEVICE_REFUSED]')).toHaveCount(0);

  // The source, placed as the preview placed it (true size, centred on the bed).
  const source = arrange(importSvg('plot-shapes.svg', readFileSync(SVG_FIXTURE, 'utf8')).paths, DEFAULT_ARRANGEMENT, BED, [0, 0]).paths.map((p) => p.points);
  // The as-drawn SVG comes from the plotter tab (the simulated pen's ink; the livedraw side of the tool).
  await expect(page.getByTestId('tab-plotter'), 'the Plotter tab, whose "Save as drawn" gives the ink').toBeVisible({ timeout: 5000 });
  await page.getByTestId('tab-plotter').click();
  const download = page.waitForEvent('download');
  await page.getByTestId('plotter-save-drawn').click();
  const drawnPath = await (await download).path();
  const drawn = savedPolylines(readFileSync(drawnPath, 'utf8'));
  expect(drawn.length).toBeGreaterThanOrEqual(4);
  const h = hausdorff(drawn, source, 0.01);
  console.log(`[plot-files] SVG: Hausdorff(as drawn, source) = ${h.toFixed(4)} mm`);
  expect(h).toBeLessThanOrEqual(DEFAULT_CHORD_TOLERANCE_MM + 0.1);
});

test('a G-code file with arcs and unknown words: warnings with line numbers, the plot completes', async ({ page }) => {
  await useBlot(page);
  await page.getByTestId('tab-plot-files').click();
  await page.getByTestId('plot-file-input').setInputFiles(GCODE_FIXTURE);
  await expect(page.getByTestId('file-summary')).toHaveAttribute('data-kind', 'gcode');
  await expect(page.getByTestId('file-summary')).toHaveAttribute('data-paths', '2');

  const warnings = page.getByTestId('file-warning');
  await expect(page.locator('[data-testid=file-warning][data-line="15"]')).toContainText('T1 is not supported');
  await expect(page.locator('[data-testid=file-warning][data-line="16"]')).toContainText('G28 is not supported');
  await expect(page.locator('[data-testid=file-warning][data-line="9"]')).toContainText("above the machine's 120 mm/s");
  await expect(page.locator('[data-testid=file-warning][data-line="12"]')).toContainText('S on M3');
  await expect(warnings).toHaveCount(4);
  const planned = await dataNumber(page, 'plot-time');
  console.log(`[plot-files] G-code: travel ${(await dataNumber(page, 'travel-before')).toFixed(1)} mm in the file's order, ${(await dataNumber(page, 'travel-after')).toFixed(1)} mm as planned; plot time ${planned.toFixed(3)} s`);
  await screenshot(page, 'plot-files-gcode-preview');

  const { elapsed_s } = await plotToCompletion(page);
  console.log(`[plot-files] G-code: ran ${elapsed_s.toFixed(3)} s of motion against ${planned.toFixed(3)} s planned`);
  expect(Math.abs(elapsed_s - planned)).toBeLessThan(0.02 * planned);
});

test('a malformed SVG is refused with its line, and the file before it stays', async ({ page }) => {
  await useBlot(page);
  await page.getByTestId('tab-plot-files').click();
  await page.getByTestId('plot-file-input').setInputFiles(SVG_FIXTURE);
  await expect(page.getByTestId('file-summary')).toContainText('plot-shapes.svg');
  await page.getByTestId('plot-file-input').setInputFiles({
    name: 'broken.svg',
    mimeType: 'image/svg+xml',
    buffer: Buffer.from('<svg xmlns="http://www.w3.org/2000/svg">\n<path d="M0 0 L10 10"/>\n<path d="M0 0 L 5 q"/>\n</svg>\n'),
  });
  await expect(page.getByTestId('file-error')).toContainText('line 3: <path> has bad path data');
  await expect(page.getByTestId('file-summary')).toContainText('plot-shapes.svg');
  // Too large: said, with Fit offered; fitting makes it plottable.
  await page.getByTestId('file-scale').fill('5');
  await page.getByTestId('file-scale').dispatchEvent('change');
  await expect(page.getByTestId('file-too-large')).toBeVisible();
  await expect(page.getByTestId('file-plot')).toBeDisabled();
  await page.getByTestId('file-offer-fit').click();
  await expect(page.getByTestId('file-too-large')).toHaveCount(0);
  await expect(page.getByTestId('file-plot')).toBeEnabled();
});

test('a G-code move the planner refuses is said with the line of the file, and not plotted', async ({ page }) => {
  await useBlot(page);
  await page.getByTestId('tab-plot-files').click();
  // F0.05 is mm/min: 0.00083 mm/s, below the slowest speed the planner takes (0.001 mm/s).
  await page.getByTestId('plot-file-input').setInputFiles({
    name: 'slow.gcode',
    mimeType: 'text/plain',
    buffer: Buffer.from('M3\nG1 X10 Y10 F600\nG1 X20 F0.05\nG1 Y20\nM5\n'),
  });
  const error = page.getByTestId('file-error');
  await expect(error).toContainText('“slow.gcode” cannot be plotted: line 3 (move');
  await expect(error).toContainText('maxVelocity: must be at least 0.001 mm/s');
  await expect(error).toHaveAttribute('data-line', '3');
  await expect(page.getByTestId('file-plot')).toBeDisabled();
});

test('a setting emptied or set to 0 is said by its field, Plot waits, and fixing it clears the message', async ({ page }) => {
  // (An error on the page, as the emptied scale once threw, fails the spec: support/test.ts.)
  await useBlot(page);
  await page.getByTestId('tab-plot-files').click();
  await page.getByTestId('plot-file-input').setInputFiles(SVG_FIXTURE);
  await expect(page.getByTestId('plot-time')).toHaveAttribute('data-value', /^\d/);
  const set = async (testId: string, value: string) => {
    await page.getByTestId(testId).fill(value);
    await page.getByTestId(testId).dispatchEvent('change');
  };
  const error = page.getByTestId('file-error');

  // An emptied scale once crashed the panel; a scale of 0 previewed a 0 × 0 mm drawing and let it be plotted.
  await set('file-scale', '');
  await expect(error).toContainText('Scale must be a number above 0');
  await expect(error).toContainText('(it is empty)');
  await expect(page.getByTestId('file-plot')).toBeDisabled();
  await set('file-scale', '0');
  await expect(error).toContainText('(it is 0)');
  // No plot time of other settings is left standing.
  await expect(page.getByTestId('plot-time')).toHaveCount(0);
  await expect(page.getByTestId('file-plot')).toBeDisabled();
  await set('file-scale', '1');
  await expect(error).toHaveCount(0);
  await expect(page.getByTestId('plot-time')).toHaveAttribute('data-value', /^\d/);
  await expect(page.getByTestId('file-plot')).toBeEnabled();

  // A pen-down speed of 0 once came back as the planner refusing "line 12" of the file, and stayed after the fix.
  await set('file-draw-speed', '0');
  await expect(error).toHaveText('“plot-shapes.svg” cannot be planned: Pen-down speed must be a speed of at least 0.001 mm/s (it is 0).');
  await expect(error).toHaveAttribute('data-line', '');
  await expect(page.getByTestId('file-plot')).toBeDisabled();
  await set('file-draw-speed', '40');
  await expect(error).toHaveCount(0);
  await expect(page.getByTestId('file-plot')).toBeEnabled();
});

test('a file of 20 000 short paths: said while it is read and planned, the page stays responsive, and it plots', async ({ page }) => {
  test.setTimeout(120_000);
  // Every main-thread task over 50 ms (the Long Tasks API reports no shorter ones).
  await page.addInitScript(() => {
    const w = window as unknown as { longTasks: number[] };
    w.longTasks = [];
    new PerformanceObserver((list) => list.getEntries().forEach((e) => w.longTasks.push(e.duration))).observe({ type: 'longtask', buffered: true });
  });
  const longTasks = () => page.evaluate(() => (window as unknown as { longTasks: number[] }).longTasks.splice(0));
  await useBlot(page);
  await page.getByTestId('tab-plot-files').click();
  // As vpype writes a dense drawing: 20 000 two-point paths scattered over a 100 mm page.
  let seed = 1;
  const random = () => (seed = (seed * 16807) % 2147483647) / 2147483647;
  const paths: string[] = [];
  for (let i = 0; i < 20_000; i++) paths.push(`<path d="M${(1 + 98 * random()).toFixed(2)} ${(1 + 98 * random()).toFixed(2)} l${(random() - 0.5).toFixed(2)} ${(random() - 0.5).toFixed(2)}"/>`);
  const svg = `<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100">\n${paths.join('\n')}\n</svg>\n`;
  await longTasks();
  await page.getByTestId('plot-file-input').setInputFiles({ name: 'dense.svg', mimeType: 'image/svg+xml', buffer: Buffer.from(svg) });

  // Seconds of work in the worker: said, and Plot waits for the plan.
  const working = page.getByTestId('file-working');
  await expect(working).toContainText('“dense.svg”');
  await expect(page.getByTestId('file-summary')).toHaveAttribute('data-paths', '20000');
  await expect(page.getByTestId('plot-time')).toHaveAttribute('data-value', /^\d/, { timeout: 60_000 });
  await expect(working).toHaveCount(0);
  await expect(page.getByTestId('file-plot')).toBeEnabled();
  const preview = page.getByTestId('file-preview');
  // Every planned path is drawn (touching ones joined: fewer than 20 000), each with its travel.
  const strokes = await dataNumber(page, 'file-preview', 'data-strokes');
  expect(strokes).toBeGreaterThan(19_000);
  expect(await dataNumber(page, 'file-preview', 'data-travel')).toBe(strokes);
  // A setting changed re-plans it; the travel in the file's order (10⁶ mm of it) is shown on demand.
  await page.getByTestId('file-rotate').selectOption('90');
  await expect(working).toHaveAttribute('data-what', 'planning');
  await expect(working).toHaveCount(0, { timeout: 60_000 });
  await page.getByTestId('file-show-before').check();
  await expect(preview).toHaveAttribute('data-show-before', 'true');
  await snapshotsPass(page, 10);
  await screenshot(page, 'plot-files-dense-preview');
  const tasks = await longTasks();
  const longest = Math.max(0, ...tasks);
  console.log(`[plot-files] 20 000 paths: ${tasks.length} main-thread tasks over 50 ms while it was read, planned, re-planned and shown (${tasks.map((t) => t.toFixed(0)).join(', ')} ms); the longest ${longest.toFixed(0)} ms`);
  // The preview once made 60 000 typed arrays and 20 000 SVG elements per plan: the page froze 1.3-2 s at each
  // plan (more on a busy machine), and 1.9 s to show the file-order travel. Now it is one canvas, whatever the
  // file: that is what is asserted. The longest task (150-400 ms here, 700 ms with both cores busy) is logged
  // above, not asserted: the specs never assert wall-clock speed.
  await expect(page.getByTestId('plot-files').locator('svg, svg *')).toHaveCount(0);

  // It plots: the job runs through its first paths; then it is cancelled (the whole takes 1 h 48 min).
  await page.getByTestId('file-plot').click();
  const progress = page.getByTestId('job-progress');
  await expect(progress).toHaveAttribute('data-phase', 'running');
  await expect.poll(async () => Number(await progress.getAttribute('data-done')), { timeout: 30_000 }).toBeGreaterThan(100);
  await page.getByTestId('job-cancel').click();
  await expect(progress).toHaveAttribute('data-phase', /cancelled|done/, { timeout: 30_000 });
});

test('a G-code file whose pen is Z0 down, Z5 up: refused with the heights it uses, the threshold set with no file loaded, and it loads', async ({ page }) => {
  await useBlot(page);
  await page.getByTestId('tab-plot-files').click();
  const file = { name: 'z-pen.gcode', mimeType: 'text/plain', buffer: Buffer.from('G21\nG90\nG0 Z5\nG0 X10 Y10\nG1 Z0 F600\nG1 X40 Y10\nG1 X40 Y30\nG0 Z5\nG0 X0 Y0\n') };
  await page.getByTestId('plot-file-input').setInputFiles(file);
  await expect(page.getByTestId('file-error')).toContainText('no move with Z below 0 mm (its Z goes from 0 to 5 mm: set Import → Z threshold');
  await expect(page.getByTestId('file-summary')).toHaveCount(0);
  // The setting the message names is there with no file loaded (it once showed only once a G-code file had loaded).
  await page.getByTestId('file-z-threshold').fill('2.5');
  await page.getByTestId('file-z-threshold').dispatchEvent('change');
  await page.getByTestId('plot-file-input').setInputFiles(file);
  await expect(page.getByTestId('file-summary')).toHaveAttribute('data-paths', '1');
  await expect(page.getByTestId('file-error')).toHaveCount(0);
  await expect(page.getByTestId('file-size')).toHaveText('30.0 × 20.0 mm');
  await expect(page.getByTestId('file-plot')).toBeEnabled();
});
