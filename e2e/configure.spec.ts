/**
 * Configure a machine, break a subscription, see the explanation where it is drawn,
 * see the core refuse it, fix it; and the configuration is kept in localStorage and
 * exported and imported as JSON.
 */
import { expect, test } from './support/test.ts';
import { readFileSync } from 'node:fs';
import { openWorkbench, screenshot } from './support/workbench.ts';

test('configure, break a subscription, see why, fix it', async ({ page }) => {
  await openWorkbench(page);
  await screenshot(page, '01-machine-view');

  await page.getByTestId('tab-configure').click();
  const editor = page.getByTestId('subscription-editor');
  await expect(editor).toBeVisible();
  // The light painter as its preset wires it: every connection valid.
  await expect(page.getByTestId('connection-motorA-stepper')).toHaveAttribute('data-problem', '');
  await expect(page.getByTestId('connection-motorA-stepper')).toHaveAttribute('data-to', 'a');

  // Change a limit: a machine configuration edit.
  await page.getByTestId('limit-velocity').fill('150');
  await page.getByTestId('limit-velocity').press('Tab');

  // Break: click motorA's position reader, then the velocity track.
  await page.getByTestId('reader-motorA-stepper').click();
  await expect(page.getByTestId('picked')).toBeVisible();
  await page.getByTestId('track-velocity').click();
  const broken = page.getByTestId('connection-motorA-stepper');
  await expect(broken).toHaveAttribute('data-to', 'velocity');
  await expect(broken).toHaveAttribute('data-problem', 'wrong kind');
  const why = page.getByTestId('problem-motorA-stepper');
  await expect(why).toContainText('is a position reader');
  await expect(why).toContainText('needs a velocity reader');
  await screenshot(page, '02-configure-broken-subscription');

  // Applying it anyway: the core refuses the whole set, listing the mismatch.
  await page.getByTestId('config-apply').click();
  await expect(page.getByTestId('phase')).toHaveText('not-ready');
  await expect(page.getByTestId('problem')).toContainText('do not match the devices');
  await expect(page.getByTestId('problem')).toContainText('"motorA"/"stepper" is a position reader');
  await expect(page.locator('[data-testid=log-entry][data-code=SUBSCRIPTION_MISMATCH]').first()).toBeVisible();

  // Fix by dragging the reader to track a.
  const from = await page.getByTestId('reader-motorA-stepper').boundingBox();
  const to = await page.getByTestId('track-a').boundingBox();
  if (!from || !to) throw new Error('editor rows not laid out');
  await page.mouse.move(from.x + from.width - 4, from.y + from.height / 2);
  await page.mouse.down();
  await page.mouse.move((from.x + to.x) / 2, (from.y + to.y) / 2, { steps: 5 });
  await page.mouse.move(to.x + 30, to.y + to.height / 2, { steps: 5 });
  await page.mouse.up();
  await expect(page.getByTestId('connection-motorA-stepper')).toHaveAttribute('data-to', 'a');
  await expect(page.getByTestId('connection-motorA-stepper')).toHaveAttribute('data-problem', '');
  await expect(page.getByTestId('problem-motorA-stepper')).toHaveCount(0);
  await page.getByTestId('config-apply').click();
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });
  await screenshot(page, '03-configure-fixed');

  // Kept in localStorage: a reload opens the edited configuration.
  await page.reload();
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });
  await page.getByTestId('tab-configure').click();
  await expect(page.getByTestId('limit-velocity')).toHaveValue('150');

  // Export, then import a changed copy.
  const [download] = await Promise.all([page.waitForEvent('download'), page.getByTestId('config-export').click()]);
  const exported = JSON.parse(readFileSync(await download.path(), 'utf8'));
  expect(exported.limits.maxVelocity).toBe(150);
  expect(exported.subscriptions).toContainEqual({ device: 'motorA', track: 'a', reader: 'stepper' });
  exported.limits.maxVelocity = 120;
  await page.getByTestId('config-import-file').setInputFiles({ name: 'machine.maxl.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(exported)) });
  await expect(page.getByTestId('limit-velocity')).toHaveValue('120');
  await expect(page.getByTestId('config-state')).toHaveText('Edited, not applied');
});
