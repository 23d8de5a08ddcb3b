/**
 * The simulated cncShield machine (an Uno with a CNC shield: x, y, z on one
 * board, the CncShield example in wasm) runs a small job: every segment done,
 * the tool back at rest, nothing refused by the board.
 */
import { expect, test } from './support/test.ts';
import { dataNumber, openWorkbench, screenshot, startJob, waitAtRest } from './support/workbench.ts';

test('the cncShield preset runs a job on its three-stepper board', async ({ page }) => {
  await openWorkbench(page);
  await page.getByTestId('machine-menu').click();
  await page.getByTestId('preset-cncShield').click();
  await expect(page.getByTestId('machine-menu')).toContainText('cncShield');
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });

  await startJob(page, { pattern: 'spiral', segments: 120, size: 40, speed: 60 });
  const progress = page.getByTestId('job-progress');
  await expect(progress).toHaveAttribute('data-phase', 'running');
  await expect(progress).toHaveAttribute('data-phase', 'done', { timeout: 60_000 });
  expect(await dataNumber(page, 'job-progress', 'data-done')).toBe(120);
  await waitAtRest(page, 15);
  await screenshot(page, 'cnc-shield-job-done');
  await expect(page.locator('[data-testid=log-entry][data-code=DEVICE_REFUSED]')).toHaveCount(0);
});
