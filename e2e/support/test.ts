/**
 * The specs' `test`: Playwright's, with one automatic check. An uncaught error on
 * the page, or an error written to its console (the worker's included), fails the
 * spec, unless it matches the short allow-list below. A workbench that throws
 * while its spec happens to pass is still broken.
 */
import { expect, test as base } from '@playwright/test';

/** Console errors that are not the workbench's, each with why it is allowed. */
const ALLOWED_CONSOLE_ERRORS: Array<{ pattern: RegExp; why: string }> = [
  // None needed so far: the whole suite runs without a console error. Add an entry
  // only for an error that is not the workbench's, with the reason.
];

export const test = base.extend<{ pageErrors: string[] }>({
  pageErrors: [
    async ({ page }, use) => {
      const errors: string[] = [];
      page.on('pageerror', (e) => errors.push(`uncaught: ${e.message}`));
      page.on('console', (msg) => {
        if (msg.type() !== 'error') return;
        const text = msg.text();
        if (!ALLOWED_CONSOLE_ERRORS.some((a) => a.pattern.test(text))) errors.push(`console: ${text}`);
      });
      await use(errors);
      expect(errors, 'errors on the page during the spec').toEqual([]);
    },
    { auto: true },
  ],
});

export { expect };
