/**
 * Jog with buttons and keys and watch the tool move in the view: taps move one
 * step exactly; holding streams motion until release, and the release's stop is
 * measured; set origin and go to origin.
 */
import type { Page } from '@playwright/test';
import { expect, test } from './support/test.ts';
import { dataNumber, openWorkbench, screenshot, snapshotsPass, waitAtRest } from './support/workbench.ts';

async function viewTool(page: Page): Promise<{ x: number; y: number }> {
  return page.evaluate(() => {
    const v = (window as unknown as { maxlView: { toolPosition: { x: number; y: number } } }).maxlView;
    return { x: v.toolPosition.x, y: v.toolPosition.y };
  });
}

test('jog with buttons and keys; hold-to-jog stops on release', async ({ page }) => {
  await openWorkbench(page);
  const start = await waitAtRest(page);

  // Button tap: one step of 10 mm in +x.
  await page.getByTestId('step-10').click();
  await page.getByTestId('jog-x+').click();
  await expect.poll(() => dataNumber(page, 'pos-x')).toBeCloseTo(start[0] + 10, 6);
  await waitAtRest(page);
  // The view's tool is where the author says.
  expect((await viewTool(page)).x).toBeCloseTo(start[0] + 10, 3);

  // Key tap: one step of 1 mm in +y.
  await page.getByTestId('step-1').click();
  await page.keyboard.press('ArrowUp');
  await expect.poll(() => dataNumber(page, 'pos-y')).toBeCloseTo(start[1] + 1, 6);
  await waitAtRest(page);

  // Set origin here, move away, go back.
  await page.getByTestId('set-origin').click();
  await expect(page.getByTestId('work-x')).toHaveText('0.000 mm');
  await page.keyboard.press('ArrowRight');
  await expect(page.getByTestId('work-x')).toHaveText('1.000 mm');
  await waitAtRest(page);
  await page.getByTestId('go-origin').click();
  await expect(page.getByTestId('work-x')).toHaveText('0.000 mm');
  await expect(page.getByTestId('work-y')).toHaveText('0.000 mm');
  const atOrigin = await waitAtRest(page);

  // Hold ArrowRight: motion streams while held…
  await page.keyboard.down('ArrowRight');
  await expect.poll(() => dataNumber(page, 'pos-x'), { timeout: 20_000 }).toBeGreaterThan(atOrigin[0] + 15);
  const tool = await viewTool(page);
  expect(tool.x).toBeGreaterThan(atOrigin[0] + 15);
  await screenshot(page, '04-jog-holding');
  // …and stops on release: the plan brakes, the tool comes to rest and stays.
  await page.keyboard.up('ArrowRight');
  await expect(page.getByTestId('jog-latency')).toBeVisible();
  const rest = await waitAtRest(page, 20);
  const report = await page.evaluate(() => (window as unknown as { maxlWorkbench: { jogReport: Record<string, number> } }).maxlWorkbench.jogReport);
  console.log(`hold-to-jog stop: ${JSON.stringify(report)}`);
  expect(report.speed).toBeGreaterThan(0);
  // Braking starts after the locked lead, not at the end of the 300 mm move (≥ 5 s away).
  expect(report.brakeLatency_ms).toBeLessThan(1000);
  // Minimal buffering: on the simulated USB link (RTT ~2 ms) the motion locked ahead
  // of the release is a few ms, not a fixed buffer. (It is counted in the machine's
  // time, so a busy test machine does not change it; getting the key to the worker,
  // delivery_ms, does depend on load and is left out.)
  expect(report.lead_ms).toBeLessThan(15);
  expect(report.lockedAhead_ms).toBeLessThan(20);
  expect(rest[0]).toBeLessThan(290);
  expect(rest[1]).toBeCloseTo(atOrigin[1], 6);
  await snapshotsPass(page, 20);
  expect(await dataNumber(page, 'pos-x')).toBe(rest[0]);
  await screenshot(page, '05-jog-stopped');
});

/**
 * A careful jog, at 1 mm/s (as when bringing a pen down to the paper): a lead's worth
 * of path is under the smallest split, and the streamer once locked the whole held
 * move: released, the tool ran on towards the soft limit (only STOP held it).
 */
test('a slow hold-to-jog (1 mm/s) stops on release too', async ({ page }) => {
  await openWorkbench(page);
  await page.getByTestId('jog-speed').fill('1');
  await page.getByTestId('jog-speed').press('Tab');
  await page.getByTestId('tab-view').click();
  const start = await waitAtRest(page);
  await page.keyboard.down('ArrowRight');
  await expect.poll(() => dataNumber(page, 'pos-x'), { timeout: 20_000 }).toBeGreaterThan(start[0] + 0.5);
  await page.keyboard.up('ArrowRight');
  await expect(page.getByTestId('jog-latency')).toBeVisible();
  const released = await dataNumber(page, 'pos-x');
  const rest = await waitAtRest(page, 20);
  // At 1 mm/s it comes to rest within a slice (0.02 mm) and the lead's motion of the release; running on, it
  // moved 1 mm a second.
  expect(rest[0] - released).toBeLessThan(0.1);
  await snapshotsPass(page, 60);
  expect(await dataNumber(page, 'pos-x')).toBe(rest[0]);
});
