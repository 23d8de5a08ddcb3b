/**
 * Choosing a machine while the page is still connecting the default one: the
 * machine chosen connects, and only it. (A choice made in the first seconds, while
 * the light painter synced its clocks, left the page at "connecting" for good.)
 */
import { expect, test } from './support/test.ts';
import type { Page } from '@playwright/test';

async function choose(page: Page, presetId: string): Promise<void> {
  await page.getByTestId('machine-menu').click();
  await page.getByTestId(`preset-${presetId}`).click();
}

test('a machine chosen while the default one connects becomes ready, alone', async ({ page }) => {
  await page.goto('/');
  await expect(page.getByTestId('phase')).not.toHaveText('ready');
  await choose(page, 'blotPlotter');
  await expect(page.getByTestId('machine-menu')).toContainText('blotPlotter');
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });
  await expect(page.locator('[data-testid=log-entry][data-code=READY]').last()).toContainText('blot');
  await expect(page.getByTestId('device')).toHaveCount(1);
  await expect(page.getByTestId('device')).toHaveAttribute('data-connection', /open/);
});

test('three machines chosen in quick succession: the last one connects, alone', async ({ page }) => {
  await page.goto('/');
  await expect(page.getByTestId('phase')).not.toHaveText('ready');
  await choose(page, 'accelRig');
  await choose(page, 'blotPlotter');
  await choose(page, 'cncShield');
  await expect(page.getByTestId('machine-menu')).toContainText('cncShield');
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });
  // The devices listed are the ones the author said it had in sync: the last choice's only.
  const ready = page.locator('[data-testid=log-entry][data-code=READY]').last();
  await expect(ready).toContainText('Ready:');
  const inSync = /Ready: (.*) in sync/.exec((await ready.textContent()) ?? '')?.[1].split(', ');
  const listed = await page.getByTestId('device').evaluateAll((els) => els.map((e) => e.getAttribute('data-name')));
  expect(listed).toEqual(inSync);
  expect(listed).toHaveLength(1);
  // The log names each machine simulated once at most, the last choice last.
  const simulated = await page.locator('[data-testid=log-entry][data-code=SIM]').allTextContents();
  expect(simulated.at(-1)).toContain('cncShield');
  expect(await page.locator('[data-testid=log-entry][data-code=READY]').count()).toBe(1);
});

test('a machine chosen while the default one is still loading its firmware: only the chosen one starts', async ({ page, context }) => {
  // Firmware that takes a while to arrive (a slow connection), so that the default
  // machine is still starting when the next is chosen.
  await context.route('**/firmware/**', async (route) => {
    await new Promise((r) => setTimeout(r, 1500));
    await route.continue();
  });
  await page.goto('/');
  await expect(page.getByTestId('phase')).toHaveText('connecting');
  await choose(page, 'blotPlotter');
  await expect(page.getByTestId('machine-menu')).toContainText('blotPlotter');
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });
  await expect(page.locator('[data-testid=log-entry][data-code=READY]').last()).toContainText('Ready: blot in sync');
  await expect(page.getByTestId('device')).toHaveCount(1);
  expect(await page.locator('[data-testid=log-entry].error').count()).toBe(0);
});
