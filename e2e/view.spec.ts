/**
 * The view shows what a user needs: the locked (transmitted) path ahead of the
 * tool is visible, a drag pans the top view (it never tilts it) and orbits the 3D
 * one, a one-axis rig is a rail, and another machine does not show the last one's
 * job. The view draws in its own worker; its pointer input is forwarded there.
 */
import type { Page } from '@playwright/test';
import { expect, test } from './support/test.ts';
import { dataNumber, openWorkbench, screenshot, startJob } from './support/workbench.ts';

/** The view's test hook: the worker that draws the view answers these two (the page awaits them). */
interface ViewHook {
  maxlView: { cameraPose: Promise<{ position: number[]; target: number[] }>; workAreaBounds: Promise<number[]> };
}

/**
 * Pixels of the view, as on screen, in the transmitted colour (#e69a1c) within a
 * tolerance. The view is drawn in a worker (its canvases are OffscreenCanvas), so
 * the page cannot read them: a screenshot of the view can. The legend, whose
 * swatch has that colour, is masked out.
 */
async function lockedPixels(page: Page): Promise<number> {
  const view = page.getByTestId('view-canvas');
  const png = await view.screenshot({ mask: [page.getByTestId('legend')] });
  return page.evaluate(async (base64) => {
    const image = await createImageBitmap(await (await fetch(`data:image/png;base64,${base64}`)).blob());
    const canvas = new OffscreenCanvas(image.width, image.height);
    const g = canvas.getContext('2d') as OffscreenCanvasRenderingContext2D;
    g.drawImage(image, 0, 0);
    const data = g.getImageData(0, 0, image.width, image.height).data;
    let n = 0;
    for (let i = 0; i < data.length; i += 4) {
      if (Math.abs(data[i] - 0xe6) < 12 && Math.abs(data[i + 1] - 0x9a) < 12 && Math.abs(data[i + 2] - 0x1c) < 12 && data[i + 3] > 200) n++;
    }
    return n;
  }, png.toString('base64'));
}

test('the locked path is visible; the top view pans; another machine drops the old job', async ({ page }) => {
  await openWorkbench(page);
  // At rest nothing is locked ahead: no transmitted colour on screen (the legend's swatch is masked).
  expect(await lockedPixels(page)).toBe(0);
  await startJob(page, { pattern: 'spiral', segments: 400, size: 60, speed: 40 });
  await expect.poll(() => dataNumber(page, 'job-progress', 'data-done'), { timeout: 30_000 }).toBeGreaterThan(20);
  // A wide orange path from the tool on (a few ms of motion: often shorter than the tool's ring), and its length in the legend.
  await expect.poll(() => lockedPixels(page), { timeout: 10_000 }).toBeGreaterThan(20);
  await expect.poll(() => dataNumber(page, 'legend-transmitted', 'data-mm')).toBeGreaterThan(0);
  await expect(page.getByTestId('legend-transmitted')).toContainText('locked ahead');
  await screenshot(page, '09-locked-path');

  // Drag in the top view: the camera moves over the bed and still looks straight down.
  const before = await page.evaluate(() => (window as unknown as ViewHook).maxlView.cameraPose);
  const box = await page.getByTestId('view-canvas').boundingBox();
  if (!box) throw new Error('no view');
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width / 2 + 120, box.y + box.height / 2 + 60, { steps: 8 });
  await page.mouse.up();
  const after = await page.evaluate(() => (window as unknown as ViewHook).maxlView.cameraPose);
  expect(Math.hypot(after.target[0] - before.target[0], after.target[1] - before.target[1])).toBeGreaterThan(1);
  expect(after.position[0]).toBeCloseTo(after.target[0], 6);
  expect(after.position[1]).toBeCloseTo(after.target[1], 6);
  expect(after.position[2] - after.target[2]).toBeCloseTo(before.position[2] - before.target[2], 6);

  // In 3D the same drag orbits: the camera turns about the target, at the same distance.
  await page.getByTestId('orbit-view').click();
  const before3d = await page.evaluate(() => (window as unknown as ViewHook).maxlView.cameraPose);
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width / 2 + 120, box.y + box.height / 2 + 60, { steps: 8 });
  await page.mouse.up();
  const after3d = await page.evaluate(() => (window as unknown as ViewHook).maxlView.cameraPose);
  const offset = (p: { position: number[]; target: number[] }) => p.position.map((v, i) => v - p.target[i]);
  for (let i = 0; i < 3; i++) expect(after3d.target[i]).toBeCloseTo(before3d.target[i], 6);
  expect(Math.hypot(...offset(after3d))).toBeCloseTo(Math.hypot(...offset(before3d)), 3);
  expect(Math.hypot(...offset(after3d).map((v, i) => v - offset(before3d)[i]))).toBeGreaterThan(1);
  await page.getByTestId('top-view').click();

  // Another machine: the one-axis rig. No trace of the last job; its travel is a rail.
  await page.getByTestId('machine-menu').click();
  await page.getByTestId('preset-accelRig').click();
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });
  await expect(page.getByTestId('job-progress')).toHaveCount(0);
  const [x0, y0, x1, y1] = await page.evaluate(() => (window as unknown as ViewHook).maxlView.workAreaBounds);
  expect(x1 - x0).toBe(300);
  expect(y1 - y0).toBeLessThan((x1 - x0) / 10);
  await screenshot(page, '10-one-axis-rail');
});

test('a browser that cannot draw the view off the main thread is told so, and the rest works', async ({ page }) => {
  await page.addInitScript(() => {
    delete (HTMLCanvasElement.prototype as unknown as { transferControlToOffscreen?: unknown }).transferControlToOffscreen;
  });
  await openWorkbench(page);
  await expect(page.locator('[data-testid=log-entry][data-code=VIEW]')).toContainText('OffscreenCanvas');
  // The machine still jogs; only the drawing is missing.
  const x0 = await dataNumber(page, 'pos-x');
  await page.getByTestId('step-10').click();
  await page.getByTestId('jog-x+').click();
  await expect.poll(() => dataNumber(page, 'pos-x')).toBeCloseTo(x0 + 10, 6);
});
