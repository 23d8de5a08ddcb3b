/**
 * STOP mid-job: every device halts (each reports it, and the simulated motors'
 * step counts stop changing), the job is over, and Re-arm makes the machine ready
 * again where it stopped.
 */
import type { Page } from '@playwright/test';
import { expect, test } from './support/test.ts';
import { dataNumber, openWorkbench, screenshot, startJob, snapshotsPass } from './support/workbench.ts';

async function motorSteps(page: Page): Promise<Record<string, number>> {
  return page.evaluate(() => ({ ...(window as unknown as { maxlWorkbench: { truth: Record<string, number> } }).maxlWorkbench.truth }));
}

for (const how of ['button', 'Escape', 'Control+Shift+E'] as const) {
  test(`STOP (${how}) mid-job halts every device`, async ({ page }) => {
    await openWorkbench(page);
    await startJob(page, { pattern: 'zigzag', segments: 300, size: 60, speed: 60 });
    await expect.poll(() => dataNumber(page, 'job-progress', 'data-done'), { timeout: 30_000 }).toBeGreaterThan(10);
    const before = await motorSteps(page);

    if (how === 'button') await page.getByTestId('stop').click();
    else await page.keyboard.press(how);

    await expect(page.getByTestId('phase')).toHaveText('halted');
    await expect(page.getByTestId('job-progress')).toHaveAttribute('data-phase', 'halted');
    // Every device says it halted.
    const devices = page.getByTestId('device');
    await expect(devices).toHaveCount(3);
    for (const d of await devices.all()) await expect(d).toHaveAttribute('data-state', 'halted');
    // And the motors do not move any more (ground truth from the simulated plant).
    const after = await motorSteps(page);
    expect(Object.keys(after).sort()).toEqual(['a', 'b']);
    expect(after).not.toEqual(before);
    await snapshotsPass(page, 30);
    expect(await motorSteps(page)).toEqual(after);
    await screenshot(page, `08-stopped-${how === 'button' ? 'button' : how === 'Escape' ? 'escape' : 'ctrl-shift-e'}`);

    // Re-arm: ready again, from where it stopped.
    await page.getByTestId('rearm').click();
    await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });
    await page.getByTestId('step-1').click();
    const x = await dataNumber(page, 'pos-x');
    await page.getByTestId('jog-x+').click();
    await expect.poll(() => dataNumber(page, 'pos-x')).toBeCloseTo(x + 1, 6);
  });
}

test('Esc with the machine menu open closes the menu and stops, and says both', async ({ page }) => {
  await openWorkbench(page);
  await startJob(page, { pattern: 'zigzag', segments: 300, size: 60, speed: 60 });
  await expect.poll(() => dataNumber(page, 'job-progress', 'data-done'), { timeout: 30_000 }).toBeGreaterThan(10);
  await page.getByTestId('machine-menu').click();
  await expect(page.getByRole('menu')).toBeVisible();

  await page.keyboard.press('Escape');
  await expect(page.getByRole('menu')).toHaveCount(0);
  await expect(page.getByTestId('phase')).toHaveText('halted');
  await expect(page.locator('[data-testid=log-entry][data-code=STOP]').filter({ hasText: 'closed the machine menu and stopped the machine' })).toHaveCount(1);
});
