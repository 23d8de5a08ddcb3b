/**
 * The WebSerial code path, end to end: a fake navigator.serial (installed with
 * addInitScript) bridged to simulated devices. "Add device" runs the app's real
 * connect code: requestPort(), open(), getInfo(), and the port's streams
 * transferred to the worker; granted ports reconnect on reload through getPorts().
 * A jog then moves the simulated motors behind the fake ports.
 */
import type { Page } from '@playwright/test';
import { expect, test } from './support/test.ts';
import path from 'node:path';
import { screenshot } from './support/workbench.ts';

const FAKE_MODULE = `/@fs${path.resolve('e2e/support/fakeSerial.ts')}`;

async function installFake(page: Page): Promise<void> {
  await page.addInitScript((url: string) => {
    // navigator.serial must exist before the app looks; the simulated devices load behind it.
    const ready = import(/* @vite-ignore */ url).then((m) => m.installFakeSerial('lightPainter'));
    const w = window as unknown as { fakeSerialReady: Promise<unknown> };
    w.fakeSerialReady = ready;
    const wait = async <T>(f: (s: { requestPort(): Promise<T>; getPorts(): Promise<T[]> }) => Promise<T | T[]>) => {
      await ready;
      return f((navigator as unknown as { serial: { requestPort(): Promise<T>; getPorts(): Promise<T[]> } }).serial);
    };
    Object.defineProperty(navigator, 'serial', {
      value: { requestPort: () => wait((s) => s.requestPort()), getPorts: () => wait((s) => s.getPorts()) },
      configurable: true,
    });
  }, FAKE_MODULE);
}

async function motorSteps(page: Page): Promise<Record<string, number>> {
  return page.evaluate(async () => {
    const control = await (window as unknown as { fakeSerialReady: Promise<{ motorSteps(): Promise<Record<string, number>> }> }).fakeSerialReady;
    return control.motorSteps();
  });
}

test('Add device runs the real WebSerial connect code against a fake navigator.serial', async ({ page }) => {
  await installFake(page);
  await page.goto('/');
  // No port is granted yet: the default simulated machine opens in the worker.
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });

  // Add the three boards of the light painter, one port each.
  for (let i = 0; i < 3; i++) {
    await page.getByTestId('machine-menu').click();
    await page.getByTestId('add-device').click();
    await expect(page.locator('[data-testid=log-entry][data-code=CONNECT]').filter({ hasText: `Connected USB 2341:${(0x43 + i).toString(16).padStart(4, '0')}` })).toHaveCount(1);
  }
  const opened = await page.evaluate(async () => ((await (window as unknown as { fakeSerialReady: Promise<{ opened: string[] }> }).fakeSerialReady).opened));
  expect(opened).toEqual(['motorA', 'motorB', 'lightPainter']);
  // The configuration kept from the simulated light painter subscribes exactly these boards.
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });
  await expect(page.getByTestId('machine-menu')).toContainText('Boards');
  const devices = page.getByTestId('device');
  await expect(devices).toHaveCount(3);
  await expect(devices.nth(0)).toHaveAttribute('data-name', 'motorA');
  await expect(devices.nth(2)).toHaveAttribute('data-name', 'lightPainter');
  await expect(devices.nth(0)).toContainText('USB 2341:0043');
  await expect(devices.nth(0)).toContainText('fw ');
  await expect(devices.nth(0).getByTestId('rtt')).toHaveText(/\d+(\.\d+)? (µs|ms)/);
  // A jog moves the motors behind the fake ports.
  const before = await motorSteps(page);
  await page.getByTestId('step-10').click();
  await page.getByTestId('jog-x+').click();
  await expect.poll(async () => Number(await page.getByTestId('pos-x').getAttribute('data-value'))).toBeCloseTo(10, 6);
  // CoreXY at 80 steps/mm: +10 mm in x is +800 steps on a and on b.
  await expect.poll(async () => (await motorSteps(page)).a - before.a, { timeout: 10_000 }).toBe(800);
  expect((await motorSteps(page)).b - before.b).toBe(800);
  // Taken once at rest: a headless screenshot holds the page's main thread, which the
  // ports' bytes cross on their way to the worker.
  await screenshot(page, '09-webserial-boards');

  // Granted ports reconnect on load.
  await page.reload();
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });
  await expect(page.getByTestId('machine-menu')).toContainText('Boards');
  await expect(page.getByTestId('device')).toHaveCount(3);
  const requests = await page.evaluate(async () => ((await (window as unknown as { fakeSerialReady: Promise<{ requests: number }> }).fakeSerialReady).requests));
  expect(requests).toBe(0);
});

test('without navigator.serial or WebUSB, the menu says what is needed', async ({ page }) => {
  await page.addInitScript(() => {
    Object.defineProperty(navigator, 'serial', { value: undefined, configurable: true });
    Object.defineProperty(navigator, 'usb', { value: undefined, configurable: true });
  });
  await page.goto('/');
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });
  await page.getByTestId('machine-menu').click();
  await expect(page.getByTestId('serial-unsupported')).toContainText('Chrome or Edge on a desktop');
  await page.getByTestId('add-device').click();
  await expect(page.locator('[data-testid=log-entry][data-code=NO_SERIAL]')).toContainText('Chrome or Edge');
});
