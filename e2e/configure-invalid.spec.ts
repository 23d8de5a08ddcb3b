/**
 * A configuration with bad fields is never applied nor saved: Apply and Export
 * wait while every problem is listed, a number field keeps what was typed (never
 * "NaN"), and Reset asks before it throws edits away.
 */
import { expect, test } from './support/test.ts';
import { openWorkbench } from './support/workbench.ts';

test('invalid fields: every problem listed, Apply refused, nothing saved; Reset asks first', async ({ page }) => {
  await openWorkbench(page);
  await page.getByTestId('tab-configure').click();

  await page.getByTestId('limit-velocity').fill('-50');
  await page.getByTestId('limit-velocity').press('Tab');
  await page.getByTestId('limit-acceleration').fill('fast');
  await page.getByTestId('limit-acceleration').press('Tab');

  // Both problems listed, not only the first; the field shows what was typed.
  const problems = page.getByTestId('config-problem');
  await expect(problems.and(page.locator('[data-field="limits.maxVelocity"]'))).toHaveCount(1);
  await expect(problems.and(page.locator('[data-field="limits.maxAcceleration"]'))).toHaveCount(1);
  await expect(page.getByTestId('limit-acceleration')).toHaveValue('fast');
  await expect(page.getByTestId('config-apply')).toBeDisabled();
  await expect(page.getByTestId('config-export')).toBeDisabled();
  await expect(page.getByTestId('config-revert')).toBeEnabled();
  await expect(page.getByTestId('config-state')).toHaveText('2 problems to fix before Apply');
  // The machine was left as it was.
  await expect(page.getByTestId('phase')).toHaveText('ready');

  // A reload brings back the last valid configuration, not the draft.
  await page.reload();
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });
  await page.getByTestId('tab-configure').click();
  await expect(page.getByTestId('limit-velocity')).toHaveValue('200');
  await expect(page.getByTestId('config-problem')).toHaveCount(0);

  // Reset asks first; keeping the configuration keeps the edit.
  await page.getByTestId('limit-velocity').fill('150');
  await page.getByTestId('limit-velocity').press('Tab');
  await page.getByTestId('config-reset').click();
  await expect(page.getByTestId('config-reset-confirm')).toBeVisible();
  await page.getByTestId('config-reset-no').click();
  await expect(page.getByTestId('config-reset-confirm')).toHaveCount(0);
  await expect(page.getByTestId('limit-velocity')).toHaveValue('150');
  // Confirmed, it goes back to the preset.
  await page.getByTestId('config-reset').click();
  await page.getByTestId('config-reset-yes').click();
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });
  await expect(page.getByTestId('limit-velocity')).toHaveValue('200');
});
