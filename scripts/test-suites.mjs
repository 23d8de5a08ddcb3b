// The suites `npm test` runs, in order, and the system tools each needs.
export const suites = [
  {
    name: 'typecheck',
    describe: 'TypeScript (strict) and Svelte type checks',
    command: ['npm', 'run', '--silent', 'typecheck'],
  },
  {
    name: 'unit',
    describe: 'vitest: the core (its layers: no import cycle or upward import, planner property tests, queue, tracks, codec vectors, sessions, clock sync, serialport link), the app units, and the simulated machine end to end in virtual time',
    command: ['npx', 'vitest', 'run'],
    tools: ['socat'],
  },
  {
    name: 'firmware-host',
    describe: 'firmware: C++ library on the host, GoogleTest via ctest (codec vs shared vectors, segment fixture, queue, braking, events, wrap)',
    command: ['bash', 'scripts/firmware-host.sh'],
    tools: ['cmake', 'make', 'c++', '/usr/include/gtest/gtest.h', '/usr/include/nlohmann/json.hpp'],
  },
  {
    name: 'firmware-avr',
    describe: 'firmware: every example built for the Arduino Uno (arduino-mk); flash/RAM table, fails under 25 % free RAM',
    command: ['bash', 'scripts/firmware-avr.sh'],
    tools: [
      'avr-gcc', 'avr-size', 'make', 'gcc', 'g++', 'simavr',
      '/usr/share/arduino/Arduino.mk', '/usr/share/arduino/hardware/arduino/avr/cores/arduino/Arduino.h',
      '/usr/include/simavr/sim_avr.h',
    ],
  },
  {
    name: 'firmware-wasm',
    describe: 'firmware: every example rebuilt to wasm32, byte-identical to public/firmware/*.wasm, instantiated in Node',
    command: ['bash', 'scripts/firmware-wasm.sh', '--check'],
    tools: [
      'clang++', 'wasm-ld', 'node', '/usr/lib/wasm32-wasi/libc.a', '/usr/lib/wasm32-wasi/libc++.a',
      '/usr/lib/llvm-14/lib/clang/*/lib/wasi/libclang_rt.builtins-wasm32.a',
    ],
  },
  {
    name: 'firmware-fuzz',
    describe: 'firmware: libFuzzer (ASan+UBSan) over the frame receiver and every handler, 25 s from the seed corpus',
    command: ['bash', 'scripts/firmware-fuzz.sh', '25'],
    tools: ['clang++', '/usr/lib/llvm-14/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a'],
  },
  {
    name: 'hil',
    describe: 'hardware in the loop: the Stepper example built for the Uno, in simavr with its UART on a pty, driven by the Node core through serialport (hello, clock sync, every step against the plan, stop, link cut)',
    command: ['bash', 'scripts/firmware-hil.sh'],
    tools: [
      'avr-gcc', 'avr-nm', 'make', 'gcc', '/usr/include/simavr/sim_avr.h',
      '/usr/share/arduino/Arduino.mk', '/usr/share/arduino/hardware/arduino/avr/cores/arduino/Arduino.h',
    ],
  },
  {
    name: 'e2e',
    describe: 'Playwright in Debian chromium: the workbench on the simulated machine (configure, jog, job, STOP, light painting) and the WebSerial path through a fake navigator.serial',
    command: ['npx', 'playwright', 'test'],
    env: { CI: '1' },
    tools: ['chromium'],
  },
  {
    name: 'e2e-built',
    describe: 'Playwright on the production build under its Content-Security-Policy (vite build + vite preview): no violation',
    command: ['npx', 'playwright', 'test', '-c', 'playwright.built.config.ts'],
    env: { CI: '1' },
    tools: ['chromium'],
  },
];
