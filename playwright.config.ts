/**
 * Playwright for the workbench's end-to-end specs (e2e/) and the UI bench. It
 * drives Debian's chromium (never a downloaded browser) against the vite dev
 * server, one spec at a time: the simulated machine runs in real time inside the
 * page's worker, so specs must not compete for the CPU.
 */
import { defineConfig } from '@playwright/test';

export const CHROMIUM_PATH = process.env.CHROMIUM_PATH ?? '/usr/bin/chromium';
export const CHROMIUM_ARGS = ['--no-sandbox', '--disable-gpu', '--disable-background-networking', '--disable-component-update', '--disable-sync'];
const PORT = Number(process.env.E2E_PORT ?? 5174);

/** What every Playwright config of the project shares: one spec at a time, Debian's chromium, no retries. */
export function sharedConfig(port: number) {
  return {
    timeout: 90_000,
    expect: { timeout: 20_000 },
    fullyParallel: false,
    workers: 1,
    // No retries: a spec that passes only sometimes is a defect to fix. (The simulated
    // machine runs on paced virtual time, so late browser timers do not reach it; the
    // WebSerial spec's real-time path has margins for the page's long tasks.)
    retries: 0,
    reporter: [['list']] as [string][],
    use: {
      baseURL: `http://localhost:${port}`,
      viewport: { width: 1280, height: 800 },
      launchOptions: { executablePath: CHROMIUM_PATH, args: CHROMIUM_ARGS },
      screenshot: 'only-on-failure' as const,
    },
  };
}

export default defineConfig({
  ...sharedConfig(PORT),
  testDir: 'e2e',
  // Specs only: e2e/support's own unit tests (*.test.ts) run under vitest.
  testMatch: '**/*.spec.ts',
  // The production build's specs run under their own config (playwright.built.config.ts).
  testIgnore: ['built/**'],
  outputDir: 'test-results/e2e',
  webServer: {
    command: `npx vite --port ${PORT} --strictPort`,
    env: { MAXL_NO_HMR: '1' },
    url: `http://localhost:${PORT}`,
    reuseExistingServer: !process.env.CI,
    timeout: 60_000,
    stdout: 'ignore',
  },
});
