/**
 * Helpers the specs share: open the workbench on a fresh simulated machine, wait
 * for conditions the page shows (never for fixed times), read numbers, and save
 * screenshots as test artifacts in test-results/screenshots/.
 */
import { expect, type Page } from '@playwright/test';

export const SCREENSHOTS = 'test-results/screenshots';

/** Opens the page with empty storage (so the default machine opens) and waits until it streams. */
export async function openWorkbench(page: Page, path = '/'): Promise<void> {
  await page.goto(path);
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });
}

/** Switches to a simulated machine from the machine menu and waits until it is ready. */
export async function usePreset(page: Page, presetId: string): Promise<void> {
  await page.getByTestId('machine-menu').click();
  await page.getByTestId(`preset-${presetId}`).click();
  await expect(page.getByTestId('machine-menu')).toContainText(presetId);
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });
}

export async function screenshot(page: Page, name: string): Promise<void> {
  await page.screenshot({ path: `${SCREENSHOTS}/${name}.png` });
}

/** Fills the job panel (pattern, segments, size mm, speed mm/s) and starts the job. */
export async function startJob(page: Page, job: { pattern: string; segments: number; size: number; speed: number }): Promise<void> {
  await page.getByTestId('job-pattern').selectOption(job.pattern);
  await page.getByTestId('job-segments').fill(String(job.segments));
  await page.getByTestId('job-size').fill(String(job.size));
  await page.getByTestId('job-speed').fill(String(job.speed));
  await page.getByTestId('job-start').click();
}

/** A number a component publishes in its data-value (or data-*) attribute. */
export async function dataNumber(page: Page, testId: string, attribute = 'data-value'): Promise<number> {
  const v = await page.getByTestId(testId).getAttribute(attribute);
  return Number(v);
}

/** Resolves once the page has received `n` more snapshots from the worker (it asks once per frame). */
export async function snapshotsPass(page: Page, n: number): Promise<void> {
  const start = await page.evaluate(() => (window as unknown as WB).maxlWorkbench.client.snapshots);
  await page.waitForFunction((target) => (window as unknown as WB).maxlWorkbench.client.snapshots >= target, start + n);
}

/** Waits until the tool has been at rest (speed 0) with an unchanged position for `n` snapshots. */
export async function waitAtRest(page: Page, n = 10): Promise<number[]> {
  return page.evaluate(
    (frames) =>
      new Promise<number[]>((resolve) => {
        const wb = (window as unknown as WB).maxlWorkbench;
        let still = 0;
        let last = '';
        const off = wb.client.on((e) => {
          if (e.type !== 'snapshot') return;
          const key = Array.from(e.position).join(',');
          still = e.speed === 0 && key === last ? still + 1 : 0;
          last = key;
          if (still >= frames) {
            off();
            resolve(Array.from(e.position));
          }
        });
      }),
    n,
  );
}

interface WB {
  maxlWorkbench: {
    client: { snapshots: number; on(h: (e: { type: string; position: Float64Array; speed: number }) => void): () => void };
  };
}
