import { defineConfig } from 'vitest/config';
import { svelte } from '@sveltejs/vite-plugin-svelte';
import { fileURLToPath } from 'node:url';

const here = fileURLToPath(new URL('.', import.meta.url));

export default defineConfig({
  root: 'app',
  publicDir: '../public',
  plugins: [svelte()],
  server: { port: 5173 },
  build: { outDir: '../dist', emptyOutDir: true },
  test: {
    root: here,
    include: ['core/**/*.test.ts'],
    setupFiles: ['core/testing/setup.ts'],
  },
});
