/**
 * Live drawing on the simulated Blot plotter: a stroke drawn with the mouse on the
 * Plotter tab's bed. The machine starts drawing it before the pointer lifts, and
 * the simulated pen's ink (read back from the "Save as drawn" SVG download)
 * matches the stroke within 0.3 mm (Hausdorff), with no ink on the travel. A tab
 * switched mid-stroke ends the stroke at its last point on the bed: the ink matches
 * what was drawn, with nothing towards the bed's edge. A stroke drawn while a file
 * plots is refused: said beside the bed, and kept whole on it as not drawn.
 */
import { readFile } from 'node:fs/promises';
import type { Page } from '@playwright/test';
import { expect, test } from './support/test.ts';
import { hausdorff, pointDrawingDistance } from '../app/tools/plotter/geometry/hausdorff.ts';
import { svgStrokes } from '../app/tools/plotter/svg/strokesSvg.ts';
import { openWorkbench, screenshot } from './support/workbench.ts';

/** The bed view's mapping from machine mm to page px (BedView publishes it on its canvas). */
async function bedMapping(page: Page): Promise<(x: number, y: number) => [number, number]> {
  const bed = page.getByTestId('plotter-bed');
  const box = (await bed.boundingBox())!;
  const attr = async (name: string) => Number(await bed.getAttribute(name));
  const [scale, ox, oy, minX, minY] = [await attr('data-scale'), await attr('data-ox'), await attr('data-oy'), await attr('data-min-x'), await attr('data-min-y')];
  return (x, y) => [box.x + ox + (x - minX) * scale, box.y + oy + (y - minY) * scale];
}

/** Opens the workbench and switches to the simulated Blot plotter, ready. */
async function openBlot(page: Page): Promise<void> {
  await openWorkbench(page);
  await page.getByTestId('machine-menu').click();
  await page.getByTestId('preset-blotPlotter').click();
  await expect(page.locator('[data-testid=log-entry][data-code=SIM]').last()).toContainText('blotPlotter');
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });
}

/** Presses the mouse at the stroke's first point (mm) and moves through the rest, 15 ms apart; the pointer stays down. */
async function pressAndMove(page: Page, toPx: (x: number, y: number) => [number, number], stroke: Array<[number, number]>): Promise<void> {
  const [sx, sy] = toPx(...stroke[0]);
  await page.mouse.move(sx, sy);
  await page.mouse.down();
  for (const p of stroke.slice(1)) {
    const [x, y] = toPx(...p);
    await page.mouse.move(x, y);
    await page.waitForTimeout(15);
  }
}

async function toolAt(page: Page): Promise<[number, number]> {
  const s = page.getByTestId('plotter-status');
  return [Number(await s.getAttribute('data-tool-x')), Number(await s.getAttribute('data-tool-y'))];
}

test('a stroke drawn with the mouse: the machine follows before the pointer lifts, and its ink matches the stroke', async ({ page }) => {
  // 120 real mouse moves, each waiting for a frame: slow on a busy machine.
  test.setTimeout(150_000);
  await openBlot(page);
  await page.getByTestId('tab-plotter').click();
  await expect(page.getByTestId('plotter-pen')).toContainText('pen');
  const toPx = await bedMapping(page);

  // An S of two arcs (radius 15 mm), drawn at about 40 mm/s: 120 pointer moves ~16 ms apart.
  const stroke: Array<[number, number]> = [];
  for (let k = 0; k <= 120; k++) {
    const u = k / 120;
    const a = u < 0.5 ? Math.PI * (1 - 2 * u) : Math.PI * (2 * u - 1) + Math.PI;
    const [cx, cy] = u < 0.5 ? [45, 60] : [75, 60];
    stroke.push([cx + 15 * Math.cos(a), cy - 15 * Math.sin(a) * (u < 0.5 ? 1 : -1)]);
  }
  const start = toPx(...stroke[0]);
  await page.mouse.move(start[0], start[1]);
  await page.mouse.down();
  let drawingFrom = 0;
  for (let k = 1; k < stroke.length; k++) {
    const [x, y] = toPx(...stroke[k]);
    await page.mouse.move(x, y);
    await page.waitForTimeout(12);
    if (k === 80) await screenshot(page, '20-plotter-draw-mid-stroke');
    if (k % 10 === 0) {
      // Drawing: the tool is on the stroke, past its first 5 mm.
      const [tx, ty] = await toolAt(page);
      const onStroke = pointDrawingDistance(tx, ty, [stroke.flat()]) < 1;
      if (onStroke && Math.hypot(tx - stroke[0][0], ty - stroke[0][1]) > 5 && drawingFrom === 0) drawingFrom = k;
    }
  }
  const behindAtLift = Number(await page.getByTestId('plotter-status').getAttribute('data-behind-mm'));
  await page.mouse.up();
  // The machine was drawing the stroke while the pointer still had most of it to go.
  expect(drawingFrom, 'the pointer move by which the machine was drawing the stroke').toBeGreaterThan(0);
  expect(drawingFrom).toBeLessThanOrEqual(60);
  console.log(`[draw] the machine was drawing the stroke by pointer move ${drawingFrom} of ${stroke.length - 1}; ${behindAtLift.toFixed(1)} mm behind at the lift`);

  // Everything drawn: the plotter lets the machine go.
  await expect(page.getByTestId('plotter-status')).toHaveAttribute('data-active', 'false', { timeout: 30_000 });
  const download = page.waitForEvent('download');
  await page.getByTestId('plotter-save-drawn').click();
  const svg = await readFile(await (await download).path(), 'utf8');
  expect(svg).toMatch(/width="125mm" height="125mm" viewBox="0 0 125 125"/);
  const ink = svgStrokes(svg);
  // One pen-down stroke: no ink on the travel to it.
  expect(ink).toHaveLength(1);
  const error = hausdorff([stroke.flat()], ink);
  console.log(`[draw] ink vs stroke: Hausdorff ${error.toFixed(3)} mm over ${ink[0].length / 2} ink points`);
  expect(error).toBeLessThanOrEqual(0.3);
  await expect(page.locator('[data-testid=log-entry][data-code=DEVICE_REFUSED]')).toHaveCount(0);
  await expect(page.locator('[data-testid=log-entry][data-code=DRAW_REFUSED]')).toHaveCount(0);

  // Bad input: a stroke that leaves the bed (y > 125 mm). The part outside is refused
  // with a note, the rest is drawn.
  const outside: Array<[number, number]> = Array.from({ length: 26 }, (_, k) => [60, 110 + k]);
  const o0 = toPx(...outside[0]);
  await page.mouse.move(o0[0], o0[1]);
  await page.mouse.down();
  for (const p of outside.slice(1)) {
    const [x, y] = toPx(...p);
    await page.mouse.move(x, y);
    await page.waitForTimeout(12);
  }
  await page.mouse.up();
  await expect(page.locator('[data-testid=log-entry][data-code=DRAW_OUTSIDE]')).toContainText(/Stroke 2 left the soft limits .*: 10\.\d mm outside were not drawn, the rest was/);
  await expect(page.getByTestId('plotter-status')).toHaveAttribute('data-active', 'false', { timeout: 30_000 });
  const download2 = page.waitForEvent('download');
  await page.getByTestId('plotter-save-drawn').click();
  const ink2 = svgStrokes(await readFile(await (await download2).path(), 'utf8'));
  expect(ink2).toHaveLength(2);
  expect(hausdorff([[60, 110, 60, 125]], [ink2[1]])).toBeLessThanOrEqual(0.3);
  await screenshot(page, '21-plotter-stroke-outside-the-bed');
});

test('switching tab mid-stroke ends the stroke where the pointer left the bed: nothing drawn that was not drawn', async ({ page }) => {
  // A second finger on a tablet, or the keyboard, can switch tabs while the pointer is still down.
  test.setTimeout(90_000);
  await openBlot(page);
  await page.getByTestId('tab-plotter').click();
  await expect(page.getByTestId('plotter-pen')).toContainText('pen');
  const toPx = await bedMapping(page);

  const stroke: Array<[number, number]> = Array.from({ length: 11 }, (_, k) => [20 + 3 * k, 100]);
  await pressAndMove(page, toPx, stroke);
  // The tab changes under the pointer (a click from script: the mouse is still down on the bed).
  await page.evaluate(() => (document.querySelector('[data-testid=tab-plot-files]') as HTMLElement).click());
  await page.mouse.move(500, 300);
  await page.mouse.up();

  await page.getByTestId('tab-plotter').click();
  await expect(page.getByTestId('plotter-status')).toHaveAttribute('data-active', 'false', { timeout: 30_000 });
  // The hidden bed once mapped the lift to (5e8, 3e8) mm: the machine inked a line to the bed's edge, and the log
  // said that 583095146.6 mm outside the bed were not drawn.
  await expect(page.locator('[data-testid=log-entry][data-code=DRAW_OUTSIDE]')).toHaveCount(0);
  const download = page.waitForEvent('download');
  await page.getByTestId('plotter-save-drawn').click();
  const ink = svgStrokes(await readFile(await (await download).path(), 'utf8'));
  expect(ink).toHaveLength(1);
  const error = hausdorff([stroke.flat()], ink);
  console.log(`[draw] tab switched mid-stroke: ink vs the stroke drawn on the bed, Hausdorff ${error.toFixed(3)} mm`);
  expect(error).toBeLessThanOrEqual(0.3);
  await screenshot(page, '22-plotter-tab-switched-mid-stroke');
});

test('a stroke drawn while a file plots is refused, said beside the bed, and kept whole on it as not drawn', async ({ page }) => {
  test.setTimeout(90_000);
  await openBlot(page);
  await page.getByTestId('tab-plot-files').click();
  await page.getByTestId('plot-file-input').setInputFiles('e2e/fixtures/plot-shapes.svg');
  await expect(page.getByTestId('file-plot')).toBeEnabled();
  await page.getByTestId('file-plot').click();
  await expect(page.getByTestId('job-progress')).toHaveAttribute('data-phase', 'running');

  await page.getByTestId('tab-plotter').click();
  // Not "Idle: draw a stroke", as it said while the plot ran.
  await expect(page.getByTestId('plotter-status')).toContainText('A job runs (“plot-shapes.svg”): a stroke is refused until it ends');
  const toPx = await bedMapping(page);
  const stroke: Array<[number, number]> = Array.from({ length: 16 }, (_, k) => [20 + 2 * k, 100]);
  await pressAndMove(page, toPx, stroke);
  await page.mouse.up();
  // The page once dropped the stroke at the refusal (a grey dot stayed on the bed) and said nothing beside it;
  // only the log, below, named the job.
  const refused = page.getByTestId('plotter-refused');
  await expect(refused).toContainText(/^Stroke \d+ was not drawn: the machine is not ready, or a job, a jog or another tool moves it/);
  await expect(refused).toHaveAttribute('data-points', String(stroke.length + 1));
  await expect(page.locator('[data-testid=log-entry][data-code=MACHINE_BUSY]').last()).toContainText('a job runs');
  await screenshot(page, '23-plotter-stroke-refused-during-a-plot');
  await expect(page.getByTestId('job-progress')).toHaveAttribute('data-phase', 'done', { timeout: 60_000 });
  // The next stroke is drawn, and the note goes.
  const [ax, ay] = toPx(30, 110);
  await page.mouse.move(ax, ay);
  await page.mouse.down();
  const [bx, by] = toPx(50, 110);
  await page.mouse.move(bx, by, { steps: 5 });
  await page.mouse.up();
  await expect(refused).toHaveCount(0);
  await expect(page.getByTestId('plotter-status')).toHaveAttribute('data-active', 'false', { timeout: 30_000 });
});
