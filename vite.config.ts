import { defineConfig } from 'vitest/config';
import { svelte } from '@sveltejs/vite-plugin-svelte';
import { fileURLToPath } from 'node:url';
import type { Plugin } from 'vite';
import { CSP_HEADER, CSP_META } from './csp.config.ts';

const here = fileURLToPath(new URL('.', import.meta.url));

/** The built index.html carries the Content-Security-Policy (csp.config.ts). */
function contentSecurityPolicy(): Plugin {
  return {
    name: 'maxl-content-security-policy',
    apply: 'build',
    transformIndexHtml: () => [{ tag: 'meta', attrs: { 'http-equiv': 'Content-Security-Policy', content: CSP_META }, injectTo: 'head-prepend' }],
  };
}

export default defineConfig({
  root: 'app',
  publicDir: '../public',
  plugins: [svelte(), contentSecurityPolicy()],
  // The e2e specs and the ui bench serve without HMR: a file saved mid-run must not reload the page under test.
  server: { port: 5173, ...(process.env.MAXL_NO_HMR ? { hmr: false, watch: null } : {}) },
  // Pre-bundle the workbench's dependencies up front: discovered later (the worker,
  // a dynamic import), vite would reload the page mid-session.
  optimizeDeps: { include: ['three', 'three/addons/controls/OrbitControls.js', 'web-serial-polyfill', 'd3-dsv'] },
  build: { outDir: '../dist', emptyOutDir: true },
  preview: { port: 4173, headers: { 'Content-Security-Policy': CSP_HEADER } },
  test: {
    root: here,
    include: ['core/**/*.test.ts', 'app/**/*.test.ts', 'e2e/support/**/*.test.ts'],
    setupFiles: ['core/testing/setup.ts'],
    // Tests run in virtual time: the timeout only guards against a hang, and must not
    // fail a long simulation on a busy machine (the default 5 s did, at 4.5 s alone).
    testTimeout: 60_000,
  },
});
