/**
 * Playwright against the production build (`vite build`, served by `vite preview`
 * with the Content-Security-Policy header): what a user deploys, under its policy.
 * Specs in e2e/built/.
 */
import { defineConfig } from '@playwright/test';
import { sharedConfig } from './playwright.config.ts';

const PORT = Number(process.env.E2E_BUILT_PORT ?? 4174);

export default defineConfig({
  ...sharedConfig(PORT),
  testDir: 'e2e/built',
  outputDir: 'test-results/e2e-built',
  webServer: {
    command: `npx vite build --logLevel warn && npx vite preview --port ${PORT} --strictPort`,
    url: `http://localhost:${PORT}`,
    reuseExistingServer: false,
    timeout: 120_000,
    stdout: 'ignore',
  },
});
