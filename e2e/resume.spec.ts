/**
 * STOP mid-job, then Resume: the same author reconnects to every board, each says
 * where it stopped, clocks re-sync, and the rest of the job runs from there to its
 * end (core: maxl.reconnect(), maxl.resumeJob()); the simulated motors stood still
 * in between.
 */
import type { Page } from '@playwright/test';
import { expect, test } from './support/test.ts';
import { dataNumber, openWorkbench, screenshot, snapshotsPass, startJob } from './support/workbench.ts';

async function motorSteps(page: Page): Promise<Record<string, number>> {
  return page.evaluate(() => ({ ...(window as unknown as { maxlWorkbench: { truth: Record<string, number> } }).maxlWorkbench.truth }));
}

test('STOP mid-job, then Resume runs the rest of the job to its end', async ({ page }) => {
  await openWorkbench(page);
  await startJob(page, { pattern: 'zigzag', segments: 120, size: 60, speed: 60 });
  await expect.poll(() => dataNumber(page, 'job-progress', 'data-done'), { timeout: 30_000 }).toBeGreaterThan(10);
  await page.getByTestId('stop').click();
  await expect(page.getByTestId('phase')).toHaveText('halted');
  await expect(page.getByTestId('job-progress')).toHaveAttribute('data-phase', 'halted');
  const total = await dataNumber(page, 'job-progress', 'data-total');
  expect(await dataNumber(page, 'job-progress', 'data-done')).toBeLessThan(total);
  // Resume is offered beside Re-arm, and nothing moves until it is pressed.
  await expect(page.getByTestId('resume-job')).toBeVisible();
  await expect(page.getByTestId('rearm')).toBeVisible();
  const stopped = await motorSteps(page);
  await snapshotsPass(page, 20);
  expect(await motorSteps(page)).toEqual(stopped);
  await screenshot(page, 'resume-offered');

  await page.getByTestId('resume-job').click();
  await expect(page.locator('[data-testid=log-entry][data-code=RESUMED]')).toHaveCount(1, { timeout: 30_000 });
  await expect(page.getByTestId('resume-job')).toHaveCount(0);
  await expect(page.getByTestId('job-progress')).toHaveAttribute('data-phase', 'done', { timeout: 90_000 });
  // Every move of the job finished, each once (done counts moves up to the last finished).
  await expect.poll(() => dataNumber(page, 'job-progress', 'data-done'), { timeout: 10_000 }).toBe(total);
  expect(await motorSteps(page)).not.toEqual(stopped);
  await expect(page.getByTestId('phase')).toHaveText('ready');
  await screenshot(page, 'resume-done');
});
