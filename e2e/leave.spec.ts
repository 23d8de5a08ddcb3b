/**
 * Closing or reloading the tab while that would lose work asks first (the
 * browser's beforeunload prompt; app/lib/leaveGuard.ts): the job runs in the
 * page's worker, so leaving ends it. With the machine at rest and nothing to
 * resume, the tab closes without a question.
 */
import type { Dialog } from '@playwright/test';
import { expect, test } from './support/test.ts';
import { openWorkbench, startJob } from './support/workbench.ts';

test('leaving the page mid-job asks first and, refused, leaves the job running; at rest it closes at once', async ({ page }) => {
  await openWorkbench(page);
  const dialogs: string[] = [];
  let answer: (d: Dialog) => Promise<void> = (d) => d.dismiss();
  page.on('dialog', (d) => {
    dialogs.push(d.type());
    void answer(d);
  });

  await startJob(page, { pattern: 'zigzag', segments: 120, size: 60, speed: 60 });
  await expect(page.getByTestId('phase')).toHaveText('running');
  // The user closes the tab, is asked, and stays.
  await page.close({ runBeforeUnload: true });
  await expect.poll(() => dialogs).toEqual(['beforeunload']);
  expect(page.isClosed()).toBe(false);
  await expect(page.getByTestId('phase')).toHaveText('running');
  const doneBefore = Number(await page.getByTestId('job-progress').getAttribute('data-done'));
  await expect.poll(async () => Number(await page.getByTestId('job-progress').getAttribute('data-done'))).toBeGreaterThan(doneBefore);

  // STOP: the job can still be resumed, so leaving asks still.
  await page.getByTestId('stop').click();
  await expect(page.getByTestId('phase')).toHaveText('halted');
  await expect(page.getByTestId('resume-job')).toBeVisible();
  await page.close({ runBeforeUnload: true });
  await expect.poll(() => dialogs).toEqual(['beforeunload', 'beforeunload']);
  expect(page.isClosed()).toBe(false);

  // Re-armed, the machine rests with no job to resume: nothing left to lose, and the tab closes at once.
  await page.getByTestId('rearm').click();
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });
  await expect(page.getByTestId('resume-job')).toHaveCount(0);
  answer = (d) => d.accept();
  const closed = page.waitForEvent('close');
  await page.close({ runBeforeUnload: true });
  await closed;
  expect(dialogs).toEqual(['beforeunload', 'beforeunload']);
});
