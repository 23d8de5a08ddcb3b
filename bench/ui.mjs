#!/usr/bin/env node
/**
 * `npm run bench -- ui`: the workbench in Debian's chromium, on the default
 * simulated machine (the light painter), measured with Playwright.
 *
 *   showMillionMs   from asking for a 1 000 000-segment job to that job drawn in the
 *                   3D view (the core's worker draws the path and transfers it to the page,
 *                   which hands it on to the view's worker; that uploads and draws it)
 *   longestTaskMs   the longest task on the page's main thread (the renderer's
 *                   CrRendererMain thread), of any length, from a Chromium trace
 *                   (the 'toplevel' category's RunTask events), while a
 *                   100 000-segment job streams with the 3D view open
 *   longTasks       of those tasks, how many took over 50 ms
 *   longestTaskCpuMs  the most CPU time (the trace's thread time) any one of those
 *                   tasks used: the main thread's own work. Where it is far below
 *                   longestTaskMs, the task spent the rest waiting for a core that
 *                   other processes held (a shared, overloaded machine)
 *   mainThreadCpuPercent  the main thread's CPU time over the window, % of one core
 *   longestReadbackMs, readbacks  the longest wait of the main thread for a WebGL
 *                   frame read back from the GPU process (GLES2::ReadPixels events on
 *                   CrRendererMain: software compositing reads a page's WebGL canvas
 *                   back there), and how many; 0 when the view draws elsewhere
 *   longestAnimationFrameMs  the longest animation frame that the Long Animation
 *                   Frames API reported meanwhile (PerformanceObserver type
 *                   'long-animation-frame': frames over 50 ms only; 0 means none),
 *                   and longestAnimationFrameWork: what it spent its time on
 *   showMillionLongestTaskMs, showMillionLongestAnimationFrameMs  the same two
 *                   figures while the million-segment job is shown
 *   maxFrameGapMs   the longest gap between animation frames meanwhile
 *   fps             animation frames per second meanwhile (the page's)
 *   viewDrawsPerSecond  draws of the 3D scene per second meanwhile (the view's
 *                   `stats.renders`; the tool's overlay is drawn every frame besides)
 *   streamedSegments  segments the machine finished in the measured window
 *   jogBrakeLatencyMs, jogRestLatencyMs  hold-to-jog: from the key's release to braking, and to rest
 *
 * Options: --seconds N (streaming window, default 20), --full (stream the whole job).
 * UI_BENCH_LOAD=N runs N CPU burners beside the bench (busy loops in child
 * processes at `nice 10`, started before vite and stopped at the end), standing in
 * for a laptop's background work; the JSON's `load` says how many. UI_BENCH_PORT
 * picks vite's port (default 5175).
 * UI_BENCH_ARGS="…" replaces chromium's flags. The default, --disable-gpu (as the e2e
 * specs run), composites in software: a WebGL canvas drawn on the page is read back
 * on the main thread (a slow software draw showed as a long task there, and
 * `readbacks` counts them); the view's worker draws on OffscreenCanvas, read back
 * on that worker's thread instead. Without it
 * (UI_BENCH_ARGS="--no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader
 * --ignore-gpu-blocklist"), WebGL and compositing run in the GPU process, as in a
 * desktop Chrome with a GPU: fps shows the software renderer's speed instead.
 * Prints one JSON object as its last line.
 */
import { chromium } from '@playwright/test';
import { spawn } from 'node:child_process';
import { setTimeout as delay } from 'node:timers/promises';
import { startTrace as startTraceOf, stopTrace as stopTraceOf } from './mainThreadTrace.mjs';

const args = process.argv.slice(2);
const seconds = Number(args[args.indexOf('--seconds') + 1]) > 0 && args.includes('--seconds') ? Number(args[args.indexOf('--seconds') + 1]) : 20;
const full = args.includes('--full');
const PORT = Number(process.env.UI_BENCH_PORT ?? 5175);
const LOAD = Math.max(0, Math.floor(Number(process.env.UI_BENCH_LOAD ?? 0)) || 0);
const URL_ = `http://localhost:${PORT}/`;
const ARGS = process.env.UI_BENCH_ARGS ? process.env.UI_BENCH_ARGS.split(' ') : ['--no-sandbox', '--disable-gpu', '--disable-background-networking', '--disable-component-update', '--disable-sync'];

// The burners: each a busy loop in its own process, at nice 10 (below the browser's priority).
const burners = Array.from({ length: LOAD }, () => spawn('nice', ['-n', '10', process.execPath, '-e', 'for (;;) {}'], { stdio: 'ignore' }));
const stopBurners = () => {
  for (const b of burners) b.kill('SIGKILL');
};
process.on('exit', stopBurners);
if (LOAD > 0) console.error(`[ui] ${LOAD} CPU burner(s) at nice 10 beside the bench`);

const server = spawn('npx', ['vite', '--port', String(PORT), '--strictPort'], { env: { ...process.env, MAXL_NO_HMR: '1' }, stdio: 'ignore', detached: true });
const stopServer = () => {
  try {
    process.kill(-server.pid, 'SIGTERM');
  } catch {
    // already gone
  }
};
process.on('exit', stopServer);

async function waitForServer() {
  for (let i = 0; i < 300; i++) {
    try {
      const r = await fetch(URL_);
      if (r.ok) return;
    } catch {
      // not yet
    }
    await delay(100);
  }
  throw new Error(`vite did not start on ${URL_}`);
}

await waitForServer();
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM_PATH ?? '/usr/bin/chromium', args: ARGS });
const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
page.on('pageerror', (e) => console.error(`[page error] ${e.message}`));
page.on('crash', () => console.error('[ui] the page crashed'));
page.on('console', (m) => { if (m.type() === 'error') console.error(`[console] ${m.text()}`); });
await page.goto(URL_);
await page.waitForFunction(() => document.querySelector('[data-testid=phase]')?.textContent === 'ready', null, { timeout: 60_000 });
console.error('[ui] workbench ready on the simulated light painter');

// Main-thread instruments: long tasks, and animation frames.
await page.evaluate(() => {
  const w = window;
  w.__bench = { loafs: [], frames: 0, maxGap: 0, last: 0, measuring: false };
  // Long animation frames (over 50 ms), with what they spent their time on.
  new PerformanceObserver((list) => {
    for (const e of list.getEntries()) {
      const scripts = (e.scripts ?? []).map((s) => `${s.invokerType} ${s.invoker} ${Math.round(s.duration)} ms`);
      // renderStart: where the frame's rendering (rAF callbacks, style, layout, paint, commit) began.
      const rendering = e.renderStart > 0 ? e.startTime + e.duration - e.renderStart : 0;
      const work = `rendering ${Math.round(rendering)} ms, blocking ${Math.round(e.blockingDuration)} ms; ${scripts.join('; ') || 'no script'}`;
      w.__bench.loafs.push({ duration: e.duration, work });
    }
  }).observe({ type: 'long-animation-frame', buffered: false });
  const frame = (t) => {
    const b = w.__bench;
    if (b.measuring) {
      b.frames++;
      if (b.last > 0) b.maxGap = Math.max(b.maxGap, t - b.last);
    }
    b.last = t;
    requestAnimationFrame(frame);
  };
  requestAnimationFrame(frame);
});
const startTrace = () => startTraceOf(browser, page);
const stopTrace = () => stopTraceOf(browser);
const resetInstruments = () =>
  page.evaluate(() => {
    Object.assign(window.__bench, { loafs: [], frames: 0, maxGap: 0, last: 0, measuring: true, t0: performance.now() });
  });
const readInstruments = () =>
  page.evaluate(() => {
    const b = window.__bench;
    b.measuring = false;
    const elapsed = (performance.now() - b.t0) / 1000;
    const loaf = b.loafs.reduce((m, e) => (e.duration > m.duration ? e : m), { duration: 0, work: '' });
    return { loaf, loafCount: b.loafs.length, fps: b.frames / elapsed, maxGap: b.maxGap, elapsed };
  });

// 1. A 100 000-segment job streaming with the 3D view open.
await page.evaluate(() => window.maxlWorkbench.startJob({ name: 'bench 100k', pattern: 'spiral', segments: 100_000, size_mm: 150, maxVelocity: 10 }));
await page.waitForFunction(() => window.maxlWorkbench.job?.phase === 'running' && window.maxlWorkbench.job.doneSegments > 0, null, { timeout: 60_000 });
await startTrace();
await resetInstruments();
const done0 = await page.evaluate(() => window.maxlWorkbench.job.doneSegments);
const renders0 = await page.evaluate(() => window.maxlView.stats.renders);
if (full) await page.waitForFunction(() => window.maxlWorkbench.job?.phase !== 'running', null, { timeout: 0 });
else await delay(seconds * 1000);
const stream = { ...(await readInstruments()), ...(await stopTrace()) };
const renders1 = await page.evaluate(() => window.maxlView.stats.renders);
const job = await page.evaluate(() => window.maxlWorkbench.job);
const errors = await page.evaluate(() => window.maxlWorkbench.log.filter((e) => e.level === 'error').map((e) => `${e.code}: ${e.message.split('\n')[0]}`));
console.error(`[ui] main thread while streaming: ${stream.tasks} tasks, longest ${stream.longest.toFixed(1)} ms (most CPU in one task ${stream.longestCpu.toFixed(1)} ms), ${stream.over50} over 50 ms, ${stream.readbacks} WebGL read-backs (longest ${stream.longestReadback.toFixed(1)} ms); longest animation frame ${stream.loaf.duration.toFixed(0)} ms (${stream.loaf.work || 'none over 50 ms'})`);
console.error(`[ui] streamed ${job.doneSegments - done0} segments in ${stream.elapsed.toFixed(1)} s; job ${job.phase}; errors: ${errors.length ? errors.slice(0, 5).join(' | ') : 'none'}`);
await page.evaluate(() => window.maxlWorkbench.send({ type: 'job-cancel' }));
await page.waitForFunction(() => ['cancelled', 'done', 'failed'].includes(window.maxlWorkbench.job?.phase), null, { timeout: 60_000 });

// A stream that went wrong leaves its author stopped: start a fresh one (Re-arm) for what follows.
const rearm = async () => {
  // The page shows 'ready' until the worker's next report: wait for a READY logged after the re-arm.
  const before = await page.evaluate(() => window.maxlWorkbench.log.at(-1)?.id ?? 0);
  await page.evaluate(() => window.maxlWorkbench.send({ type: 'rearm' }));
  await page.waitForFunction((id) => window.maxlWorkbench.log.some((e) => e.id > id && e.code === 'READY') && window.maxlWorkbench.machine?.phase === 'ready', before, { timeout: 60_000 });
};
await rearm();

// 2. A 1 000 000-segment job, shown in the view.
await startTrace();
await resetInstruments();
const showMillionMs = await page.evaluate(
  () =>
    new Promise((resolve) => {
      const t0 = performance.now();
      window.maxlWorkbench.startJob({ name: 'bench 1M', pattern: 'spiral', segments: 1_000_000, size_mm: 150, maxVelocity: 25 });
      const check = () => {
        if (window.maxlView.stats.previewSegments === 1_000_000) {
          // Drawn in this frame's task; the next frame is on screen.
          requestAnimationFrame(() => resolve(performance.now() - t0));
        } else requestAnimationFrame(check);
      };
      check();
    }),
);
const million = { ...(await readInstruments()), ...(await stopTrace()) };
console.error(`[ui] 1 000 000 segments shown in ${showMillionMs.toFixed(0)} ms (longest task then ${million.longest.toFixed(0)} ms)`);
await page.evaluate(() => window.maxlWorkbench.send({ type: 'job-cancel' }));
await page.waitForFunction(() => ['cancelled', 'failed', 'done', 'halted'].includes(window.maxlWorkbench.job?.phase), null, { timeout: 60_000 });
console.error(`[ui] the 1M job ended: ${await page.evaluate(() => window.maxlWorkbench.job.phase)}`);

await rearm();

// 3. Hold-to-jog: hold → for 1 s, release, read the stop the worker measured.
await page.evaluate(() => window.maxlWorkbench.send({ type: 'go-to-origin', speed: 100 }));
await page
  .waitForFunction(() => window.maxlWorkbench.speed === 0 && Math.abs(window.maxlWorkbench.position[0]) < 1e-6, null, { timeout: 60_000 })
  .catch(async (err) => {
    const state = await page.evaluate(() => ({ position: window.maxlWorkbench.position, speed: window.maxlWorkbench.speed, phase: window.maxlWorkbench.machine?.phase, log: window.maxlWorkbench.log.slice(-5).map((e) => `${e.code}: ${e.message}`) }));
    throw new Error(`go to origin did not end at the origin: ${JSON.stringify(state)} (${err.message})`);
  });
await page.keyboard.down('ArrowRight');
await delay(1000);
await page.keyboard.up('ArrowRight');
await page.waitForFunction(() => window.maxlWorkbench.jogReport !== null, null, { timeout: 10_000 });
const jog = await page.evaluate(() => window.maxlWorkbench.jogReport);
// Which WebGL renderer drew it: here always a software one (SwiftShader), which is
// what bounds fps and, with --disable-gpu, the main thread's longest task.
const renderer = await page.evaluate(() => {
  const gl = document.createElement('canvas').getContext('webgl2');
  const info = gl?.getExtension('WEBGL_debug_renderer_info');
  return info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : 'unknown';
});

await browser.close();
stopServer();
stopBurners();
const result = {
  bench: 'ui',
  load: LOAD,
  longestTaskMs: Math.round(stream.longest * 10) / 10,
  longTasks: stream.over50,
  longestTaskCpuMs: Math.round(stream.longestCpu * 10) / 10,
  mainThreadCpuPercent: Math.round((stream.cpuTotal / 1000 / stream.elapsed) * 1000) / 10,
  longestReadbackMs: Math.round(stream.longestReadback * 10) / 10,
  readbacks: stream.readbacks,
  mainThreadTasks: stream.tasks,
  longestAnimationFrameMs: Math.round(stream.loaf.duration * 10) / 10,
  longestAnimationFrameWork: stream.loaf.work,
  maxFrameGapMs: Math.round(stream.maxGap * 10) / 10,
  fps: Math.round(stream.fps * 10) / 10,
  viewDrawsPerSecond: Math.round(((renders1 - renders0) / stream.elapsed) * 10) / 10,
  showMillionMs: Math.round(showMillionMs),
  showMillionLongestTaskMs: Math.round(million.longest * 10) / 10,
  showMillionLongestTaskCpuMs: Math.round(million.longestCpu * 10) / 10,
  showMillionLongestAnimationFrameMs: Math.round(million.loaf.duration * 10) / 10,
  streamedSegments: job.doneSegments - done0,
  streamSeconds: Math.round(stream.elapsed * 10) / 10,
  jobSegments: 100_000,
  streamErrors: errors.length,
  jogSpeedMmPerS: jog.speed,
  jogBrakeLatencyMs: Math.round(jog.brakeLatency_ms * 10) / 10,
  jogRestLatencyMs: Math.round(jog.restLatency_ms * 10) / 10,
  jogLeadMs: Math.round(jog.lead_ms * 10) / 10,
  jogDeliveryMs: Math.round(jog.delivery_ms * 10) / 10,
  jogLockedAheadMs: Math.round(jog.lockedAhead_ms * 10) / 10,
  webglRenderer: renderer,
  chromiumArgs: ARGS.join(' '),
  targets: { longestTaskMs: 50, showMillionMs: 2000 },
};
console.log(JSON.stringify(result));
process.exit(0);
