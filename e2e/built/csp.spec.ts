/**
 * The production build under its Content-Security-Policy (csp.config.ts,
 * docs/security.md): the policy is in force (meta tag and header), the workbench
 * starts its worker, runs the firmware as wasm and a job, and the browser reports
 * no violation of the policy.
 */
import { expect, test } from '../support/test.ts';

test('the built app works under its Content-Security-Policy, with no violation', async ({ page, pageErrors }) => {
  await page.addInitScript(() => {
    const w = window as unknown as { cspViolations: string[] };
    w.cspViolations = [];
    document.addEventListener('securitypolicyviolation', (e) => w.cspViolations.push(`${e.violatedDirective}: ${e.blockedURI}`));
  });
  const response = await page.goto('/');
  const header = response?.headers()['content-security-policy'] ?? '';
  expect(header).toContain("script-src 'self' 'wasm-unsafe-eval'");
  expect(header).not.toContain('unsafe-inline');
  expect(header).not.toMatch(/'unsafe-eval'/);
  await expect(page.locator('meta[http-equiv="Content-Security-Policy"]')).toHaveCount(1);

  // The policy really is enforced: an inline script is refused.
  const inlineRan = await page.evaluate(async () => {
    const s = document.createElement('script');
    s.textContent = 'window.inlineRan = true';
    document.head.appendChild(s);
    await new Promise((r) => setTimeout(r, 50));
    return (window as unknown as { inlineRan?: boolean }).inlineRan === true;
  });
  expect(inlineRan).toBe(false);
  const refused = await page.evaluate(() => (window as unknown as { cspViolations: string[] }).cspViolations.splice(0));
  expect(refused.some((v) => v.startsWith('script-src'))).toBe(true);
  // The browser said so on the console: the one error this spec expects, and takes off the list.
  expect(pageErrors.length).toBeGreaterThan(0);
  expect(pageErrors.every((e) => e.includes('Executing inline script violates'))).toBe(true);
  pageErrors.splice(0);

  // The worker, the wasm firmware and a job, under the policy.
  await expect(page.getByTestId('phase')).toHaveText('ready', { timeout: 30_000 });
  await page.getByTestId('job-pattern').selectOption('spiral');
  await page.getByTestId('job-segments').fill('200');
  await page.getByTestId('job-start').click();
  await expect(page.getByTestId('job-progress')).toHaveAttribute('data-phase', 'done', { timeout: 60_000 });
  expect(await page.evaluate(() => (window as unknown as { cspViolations: string[] }).cspViolations)).toEqual([]);
});
