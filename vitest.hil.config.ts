// The hardware-in-the-loop suite (scripts/firmware-hil.sh): the Uno build of the
// firmware in simavr behind a pseudo-terminal, driven by the Node core. Apart from
// `npm test`'s unit suite because it needs the AVR build first and runs for tens of
// seconds; its files are core/**/*.hil.ts, which the unit suite does not match.
import { defineConfig } from 'vitest/config';
import { fileURLToPath } from 'node:url';

export default defineConfig({
  test: {
    root: fileURLToPath(new URL('.', import.meta.url)),
    include: ['core/**/*.hil.ts'],
    setupFiles: ['core/testing/setup.ts'],
    // Lockstep holds on any host, only slower: ~30 s of real time on a quiet machine,
    // ~100 s on 2 cores with a dozen busy processes.
    testTimeout: 240_000,
    hookTimeout: 120_000,
  },
});
