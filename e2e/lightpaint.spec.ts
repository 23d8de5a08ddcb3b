/**
 * Light-paint a word through the UI on the simulated light painter, save the
 * exposure as PNG (a real download), and read it back column by column against
 * the bitmap: every lit column lit, every dark one dark, and every run of lit
 * columns placed within a quarter of the pixel pitch (exposureAnalysis.ts).
 */
import { readFileSync } from 'node:fs';
import type { Page } from '@playwright/test';
import { expect, test } from './support/test.ts';
import { analyseColumns, type ExposureChannel } from '../app/tools/lightpaint/exposureAnalysis.ts';
import { srgbToLinear } from '../app/tools/lightpaint/exposureFrame.ts';
import type { RasterLayout } from '../app/tools/lightpaint/raster.ts';
import { openWorkbench, screenshot } from './support/workbench.ts';

/**
 * The PNG's red channel (the colour's brightest), decoded by the browser, as linear
 * light on 0..255: the PNG is sRGB-encoded, as a camera writes (exposureFrame.ts).
 */
async function decodePng(page: Page, png: Buffer): Promise<{ width: number; height: number; red: number[] }> {
  const decoded = await page.evaluate(async (b64) => {
    const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const img = await createImageBitmap(new Blob([bytes], { type: 'image/png' }));
    const c = new OffscreenCanvas(img.width, img.height);
    const g = c.getContext('2d')!;
    g.drawImage(img, 0, 0);
    const data = g.getImageData(0, 0, img.width, img.height).data;
    const red: number[] = [];
    for (let k = 0; k < data.length; k += 4) red.push(data[k]);
    return { width: img.width, height: img.height, red };
  }, png.toString('base64'));
  return { ...decoded, red: decoded.red.map((v) => 255 * srgbToLinear(v / 255)) };
}

test.use({ viewport: { width: 1600, height: 1000 } });

test('light-paint a word: the saved exposure shows every column where the bitmap puts it', async ({ page }) => {
  await openWorkbench(page);
  await page.getByTestId('tab-lightpaint').click();
  await page.getByTestId('lightpaint-source-text').click();
  await page.getByTestId('lightpaint-text').fill('MAXL');
  await page.getByTestId('lightpaint-speed').fill('200');
  await expect(page.getByTestId('lightpaint-bitmap')).toHaveAttribute('data-width', '23');
  await page.getByTestId('lightpaint-clear').click();
  await page.getByTestId('lightpaint-start').click();

  const progress = page.getByTestId('job-progress');
  await expect(progress).toHaveAttribute('data-phase', 'running');
  await expect(progress).toHaveAttribute('data-phase', 'done', { timeout: 60_000 });
  const layoutEl = page.getByTestId('lightpaint-layout');
  const layout = JSON.parse((await layoutEl.getAttribute('data-layout')) as string) as RasterLayout;
  const ledOffsets = JSON.parse((await layoutEl.getAttribute('data-led-offsets')) as string) as number[];
  expect(layout.bits).toHaveLength(23);
  await screenshot(page, 'lightpaint-exposure');

  const downloading = page.waitForEvent('download');
  await page.getByTestId('lightpaint-save').click();
  const download = await downloading;
  expect(download.suggestedFilename()).toBe('lightpaint-exposure.png');
  const png = readFileSync((await download.path()) as string);
  const { width, height, red } = await decodePng(page, png);
  const canvas = page.getByTestId('lightpaint-exposure');
  expect(width).toBe(Number(await canvas.getAttribute('data-width')));
  expect(height).toBe(Number(await canvas.getAttribute('data-height')));
  const mmPerPixel = Number(await canvas.getAttribute('data-mm-per-pixel'));
  // The PNG's top row is the largest y: turn it the machine's way up (j grows with y).
  const values = new Float64Array(width * height);
  for (let j = 0; j < height; j++) for (let i = 0; i < width; i++) values[j * width + i] = red[(height - 1 - j) * width + i];
  const exposure: ExposureChannel = {
    width,
    height,
    mmPerPixel,
    origin_mm: [Number(await canvas.getAttribute('data-origin-x')), Number(await canvas.getAttribute('data-origin-y'))],
    values,
  };
  // At least 4 pixels per pitch.
  expect(layout.pitch_mm / mmPerPixel).toBeGreaterThanOrEqual(4);
  const a = analyseColumns(exposure, layout, ledOffsets);
  console.log(
    `lightpaint e2e: ${a.runs.length} runs, placement ${a.placementError_mm.toFixed(3)} mm, edges ${a.edgeError_mm.toFixed(3)} mm, darkest lit ${a.minLit.toFixed(2)}, brightest dark ${a.maxDark.toFixed(2)}`,
  );
  expect(a.litLevel).toBeGreaterThan(50);
  expect(a.mismatches).toEqual([]);
  expect(a.placementError_mm).toBeLessThanOrEqual(layout.pitch_mm / 4);
});

test('bad input is refused with words: empty text, a picture too wide (with a pitch that fits), speed above the limit', async ({ page }) => {
  await openWorkbench(page);
  await page.getByTestId('tab-lightpaint').click();
  await page.getByTestId('lightpaint-text').fill('   ');
  await expect(page.getByTestId('lightpaint-input-error')).toHaveText(/Type some text/);
  await expect(page.getByTestId('lightpaint-start')).toBeDisabled();

  // An image that does not decode: said, and nothing to paint.
  await page.getByTestId('lightpaint-source-image').click();
  await page.getByTestId('lightpaint-image').setInputFiles({ name: 'broken.png', mimeType: 'image/png', buffer: Buffer.from('not a png at all') });
  await expect(page.getByTestId('lightpaint-problem')).toHaveText(/“broken\.png” could not be decoded/);
  await expect(page.getByTestId('lightpaint-start')).toBeDisabled();
  // A real one (a 1 × 1 white PNG made by the browser): scaled to the strip and lit.
  const white = await page.evaluate(async () => {
    const c = new OffscreenCanvas(4, 4);
    const g = c.getContext('2d')!;
    g.fillStyle = 'white';
    g.fillRect(0, 0, 4, 4);
    const blob = await c.convertToBlob({ type: 'image/png' });
    return Array.from(new Uint8Array(await blob.arrayBuffer()));
  });
  await page.getByTestId('lightpaint-image').setInputFiles({ name: 'white.png', mimeType: 'image/png', buffer: Buffer.from(white) });
  // 4 × 4 px on 8 LEDs 6.4 mm apart at a 2 mm pitch: 8 · 6.4 / 2 ≈ 26 columns.
  await expect(page.getByTestId('lightpaint-bitmap')).toHaveAttribute('data-width', '26');
  await page.getByTestId('lightpaint-source-text').click();

  await page.getByTestId('lightpaint-speed').fill('500');
  await expect(page.getByTestId('lightpaint-capped')).toHaveText(/limit is 200 mm\/s/);
  await page.getByTestId('lightpaint-speed').fill('200');

  await page.getByTestId('lightpaint-text').fill('HELLO WORLD HELLO WORLD HELLO');
  await page.getByTestId('lightpaint-pitch').fill('3');
  await page.getByTestId('lightpaint-start').click();
  await expect(page.getByTestId('lightpaint-problem')).toHaveText(/mm missing/);
  await screenshot(page, 'lightpaint-too-wide');
  await page.getByTestId('lightpaint-fit').click();
  const pitch = Number(await page.getByTestId('lightpaint-pitch').inputValue());
  expect(pitch).toBeLessThan(3);
  // Slower, so the pass (about 290 mm) lasts some 15 s and Cancel finds it running even
  // on a busy machine (at 200 mm/s it could end before the click); the fitted pitch still
  // fits, as the run-up only shortens.
  await page.getByTestId('lightpaint-speed').fill('20');
  await page.getByTestId('lightpaint-start').click();
  await expect(page.getByTestId('job-progress')).toHaveAttribute('data-phase', 'running');
  await expect(page.getByTestId('lightpaint-problem')).toHaveCount(0);
  await page.getByTestId('job-cancel').click();
  await expect(page.getByTestId('job-progress')).toHaveAttribute('data-phase', 'cancelled');
});

test('a bitmap painted on the grid is what the strip writes', async ({ page }) => {
  await openWorkbench(page);
  await page.getByTestId('tab-lightpaint').click();
  await page.getByTestId('lightpaint-source-paint').click();
  await page.getByTestId('lightpaint-columns').fill('4');
  await page.getByTestId('lightpaint-columns').press('Tab');
  await expect(page.getByTestId('lightpaint-bitmap')).toHaveAttribute('data-width', '4');
  // Row 0 is the top (LED 7), row 7 the bottom (LED 0).
  await page.getByTestId('lightpaint-cell-0-0').click();
  await page.getByTestId('lightpaint-cell-7-0').click();
  await page.getByTestId('lightpaint-cell-3-2').click();
  await page.getByTestId('lightpaint-start').click();
  await expect(page.getByTestId('job-progress')).toHaveAttribute('data-phase', 'done', { timeout: 60_000 });
  const layout = JSON.parse((await page.getByTestId('lightpaint-layout').getAttribute('data-layout')) as string) as RasterLayout;
  expect(layout.bits).toEqual([0b10000001, 0, 1 << 4, 0]);
});

test('an image too wide for the bed is told to be cropped, never offered a pitch (a finer pitch only adds columns)', async ({ page }) => {
  await openWorkbench(page);
  await page.getByTestId('tab-lightpaint').click();
  await page.getByTestId('lightpaint-source-image').click();
  // 2000 × 100 px: 20 × the strip's 51.2 mm = 1024 mm along x at any pitch.
  const wide = await page.evaluate(async () => {
    const c = new OffscreenCanvas(2000, 100);
    const g = c.getContext('2d')!;
    g.fillStyle = 'white';
    g.fillRect(0, 0, 2000, 100);
    const blob = await c.convertToBlob({ type: 'image/png' });
    return Array.from(new Uint8Array(await blob.arrayBuffer()));
  });
  await page.getByTestId('lightpaint-image').setInputFiles({ name: 'banner.png', mimeType: 'image/png', buffer: Buffer.from(wide) });
  await expect(page.getByTestId('lightpaint-bitmap')).toHaveAttribute('data-width', '512');
  await page.getByTestId('lightpaint-start').click();
  await expect(page.getByTestId('lightpaint-problem')).toHaveText(/1024\.2 mm along x.*crop the image/);
  await expect(page.getByTestId('lightpaint-problem')).not.toHaveText(/pitch of/);
  // Once offered “a pitch of 0.58 mm”: 1765 columns, still 1024 mm, and a smaller pitch offered again.
  await expect(page.getByTestId('lightpaint-fit')).toHaveCount(0);
  await screenshot(page, 'lightpaint-image-too-wide');
});

test('the bitmap preview draws each cell as tall against its width as on the machine (LED spacing ÷ pitch)', async ({ page }) => {
  await openWorkbench(page);
  await page.getByTestId('tab-lightpaint').click();
  await page.getByTestId('lightpaint-source-text').click();
  await page.getByTestId('lightpaint-text').fill('HI');
  const ratio = async () => {
    const box = (await page.getByTestId('lightpaint-cell-0-0').boundingBox())!;
    return box.height / box.width;
  };
  // 2 mm along the move, 6.4 mm between LEDs: 3.2 times as tall as wide, as the photo shows
  // them (square cells once drew the letters 3.2 times wider than the strip paints them).
  await page.getByTestId('lightpaint-pitch').fill('2');
  await expect(page.getByTestId('lightpaint-bitmap')).toHaveAttribute('data-width', '11');
  expect(Math.abs((await ratio()) / 3.2 - 1)).toBeLessThan(0.1);
  await expect(page.getByTestId('lightpaint-size')).toContainText('22.0 mm along x × 51.2 mm across');
  await screenshot(page, 'lightpaint-preview-aspect');
  await page.getByTestId('lightpaint-pitch').fill('6.4');
  await expect(page.getByTestId('lightpaint-bitmap')).toHaveAttribute('data-aspect', '1');
  expect(Math.abs((await ratio()) - 1)).toBeLessThan(0.1);
});
