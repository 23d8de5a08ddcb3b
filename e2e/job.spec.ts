/**
 * Run a small job with a progress bar and ETA; pause (the tool comes to rest on
 * the path and stays), resume (it goes on), cancel (it stops on the path, the rest
 * is dropped).
 */
import { expect, test } from './support/test.ts';
import { dataNumber, openWorkbench, screenshot, startJob, snapshotsPass, waitAtRest } from './support/workbench.ts';

test('a small job: progress, pause, resume, cancel', async ({ page }) => {
  await openWorkbench(page);
  await startJob(page, { pattern: 'spiral', segments: 400, size: 60, speed: 40 });

  const progress = page.getByTestId('job-progress');
  await expect(progress).toHaveAttribute('data-phase', 'running');
  await expect(progress).toHaveAttribute('data-total', '400');
  // The whole job is in the view at once.
  await expect(page.getByTestId('legend')).toHaveAttribute('data-preview', '400');
  await expect.poll(() => dataNumber(page, 'job-progress', 'data-done'), { timeout: 30_000 }).toBeGreaterThan(40);
  await expect(page.getByTestId('job-eta')).toHaveText(/ETA \d+ (s|min)/);
  // The header says what the machine does, and the bar draws what the text says.
  await expect(page.getByTestId('phase')).toHaveText('running');
  const [drawn, told] = await page.evaluate(() => {
    const fill = document.querySelector('[data-testid=job-progress-fill]') as HTMLElement;
    const bar = fill.parentElement as HTMLElement;
    const fraction = Number(document.querySelector('[data-testid=job-progress]')?.getAttribute('data-fraction'));
    return [fill.getBoundingClientRect().width / bar.getBoundingClientRect().width, fraction];
  });
  expect(Math.abs(drawn - told)).toBeLessThan(0.01);
  await screenshot(page, '06-job-running');

  // Pause: brakes to rest on the path and holds.
  await page.getByTestId('job-pause').click();
  await expect(progress).toHaveAttribute('data-phase', 'paused');
  await expect(page.getByTestId('phase')).toHaveText('paused');
  const held = await waitAtRest(page, 15);
  const doneAtPause = await dataNumber(page, 'job-progress', 'data-done');
  await snapshotsPass(page, 30);
  expect(await dataNumber(page, 'pos-x')).toBe(held[0]);
  expect(await dataNumber(page, 'pos-y')).toBe(held[1]);
  expect(await dataNumber(page, 'job-progress', 'data-done')).toBe(doneAtPause);
  await screenshot(page, '07-job-paused');

  // Resume: it goes on from there.
  await page.getByTestId('job-resume').click();
  await expect(progress).toHaveAttribute('data-phase', 'running');
  await expect.poll(() => dataNumber(page, 'job-progress', 'data-done'), { timeout: 30_000 }).toBeGreaterThan(doneAtPause + 20);

  // Cancel: stops on the path; the rest of the job is dropped.
  await page.getByTestId('job-cancel').click();
  await expect(progress).toHaveAttribute('data-phase', 'cancelled');
  await waitAtRest(page, 15);
  const done = await dataNumber(page, 'job-progress', 'data-done');
  expect(done).toBeLessThan(400);
  await snapshotsPass(page, 30);
  expect(await dataNumber(page, 'job-progress', 'data-done')).toBe(done);
  await expect(page.getByTestId('speed')).toHaveText('0.0 mm/s');
  await expect(page.getByTestId('phase')).toHaveText('ready');
  await expect(page.locator('[data-testid=log-entry][data-code=JOB]').last()).toContainText('cancelled');
  // Nothing the machine refused along the way.
  await expect(page.locator('[data-testid=log-entry][data-code=DEVICE_REFUSED]')).toHaveCount(0);
  await expect(page.locator('[data-testid=log-entry][data-code=LINK_LOST]')).toHaveCount(0);
});

/**
 * A job of tiny fast segments (2 000 000 in a 150 mm spiral, 24 µm each, at 200 mm/s):
 * the devices' 64-segment queues cannot hold its braking distance, a buffer
 * conflict (core/net/streamer.ts). The author brakes the machine to rest and
 * streams no more, so the job ends, failed, with the reason, and the header says
 * "stopped" with Re-arm; before, the job stayed "running" at its last count with its
 * ETA frozen. Re-armed, a job at a sensible speed runs to its end.
 */
test('a buffer conflict ends the job and stops the machine, saying why; Re-arm runs the next job', async ({ page }) => {
  await openWorkbench(page);
  await startJob(page, { pattern: 'spiral', segments: 2_000_000, size: 150, speed: 200 });
  await expect(page.locator('[data-testid=log-entry][data-code=BUFFER_CONFLICT]')).toHaveCount(1, { timeout: 30_000 });
  await expect(page.getByTestId('job-progress')).toHaveAttribute('data-phase', 'failed');
  await expect(page.locator('[data-testid=log-entry][data-code=JOB_FAILED]').last()).toContainText('a buffer conflict stopped the stream');
  await expect(page.getByTestId('phase')).toHaveText('stopped');
  await expect(page.getByTestId('phase')).toHaveAttribute('title', /buffer conflict: segment \d+/);
  await expect(page.getByTestId('resume-job')).toHaveCount(0);

  await page.getByTestId('rearm').click();
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });
  await startJob(page, { pattern: 'spiral', segments: 200, size: 20, speed: 40 });
  await expect(page.getByTestId('job-progress')).toHaveAttribute('data-phase', 'done', { timeout: 60_000 });
});
