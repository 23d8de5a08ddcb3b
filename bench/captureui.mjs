#!/usr/bin/env node
/**
 * `npm run bench -- captureui`: the capture tool in Debian's chromium on the simulated
 * accelRig (the Accelerometer example), a resonance sweep of 15 → 40 Hz over --seconds
 * (default 5), then a zoom and the CSV export, the page's main thread traced in each.
 *
 *   samples            samples captured (the tool's own count, data-value of capture-samples)
 *   sampleRateHz       samples / the capture's span (the CSV's first to last author_us)
 *   plotSamples        samples the measured line is drawn from (its data-samples)
 *   plotPoints         points of that line as drawn, full view (min/max decimation: at
 *                      most 4 a pixel column)
 *   csvRows            rows of the CSV downloaded
 *   csvExportMs        from the click on CSV to the download
 *   captureLongTasks   over the whole capture, from Run to the result shown: the tasks
 *                      over 50 ms the Long Tasks API reported (wall time), how many and
 *                      the longest
 *   capture, zoom, csv: the main thread's tasks from a Chromium trace (mainThreadTrace.mjs,
 *                      as bench/ui.mjs reads them) over the capture's last 3 s to the
 *                      result shown (the record's arrival, its first draw), while zooming
 *                      (8 wheel steps and a cursor read), while exporting the CSV:
 *     longestTaskMs      the longest task, wall time
 *     longestTaskCpuMs   the most CPU time (the trace's thread time) one task used: on a
 *                        loaded machine, wall time includes waiting for a core
 *     over50             tasks over 50 ms (wall)
 *     tasks              tasks in all
 *
 * Options: --seconds N (the sweep's length, s; default 5). CAPTURE_UI_PORT picks vite's
 * port (default 5176). Prints one JSON object as its last line.
 */
import { chromium } from '@playwright/test';
import { spawn } from 'node:child_process';
import { readFile } from 'node:fs/promises';
import { setTimeout as delay } from 'node:timers/promises';
import { csvParse } from 'd3-dsv';
import { startTrace, stopTrace } from './mainThreadTrace.mjs';

const args = process.argv.slice(2);
const seconds = args.includes('--seconds') ? Number(args[args.indexOf('--seconds') + 1]) : 5;
if (!(seconds > 0)) throw new Error(`--seconds must be a positive number (got ${args[args.indexOf('--seconds') + 1]})`);
const PORT = Number(process.env.CAPTURE_UI_PORT ?? 5176);
const URL_ = `http://localhost:${PORT}/`;
/** The trace's categories: the main thread's tasks only. */
const TRACE = ['toplevel', '__metadata'];
const ARGS = ['--no-sandbox', '--disable-gpu', '--disable-background-networking', '--disable-component-update', '--disable-sync'];

const server = spawn('npx', ['vite', '--port', String(PORT), '--strictPort'], { env: { ...process.env, MAXL_NO_HMR: '1' }, stdio: 'ignore', detached: true });
process.on('exit', () => {
  try {
    process.kill(-server.pid, 'SIGTERM');
  } catch {
    // already gone
  }
});

async function waitForServer() {
  for (let i = 0; i < 600; i++) {
    try {
      if ((await fetch(URL_)).ok) return;
    } catch {
      // not yet
    }
    await delay(100);
  }
  throw new Error(`vite did not start on ${URL_}`);
}

await waitForServer();
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM_PATH ?? '/usr/bin/chromium', args: ARGS });
const page = await browser.newPage({ viewport: { width: 1280, height: 800 }, acceptDownloads: true });
page.on('pageerror', (e) => console.error(`[page error] ${e.message}`));
const byId = (id) => page.getByTestId(id);
const phaseIs = (text) => page.waitForFunction((t) => document.querySelector('[data-testid=phase]')?.textContent === t, text, { timeout: 120_000 });

await page.goto(URL_);
await phaseIs('ready');
await byId('machine-menu').click();
await byId('preset-accelRig').click();
await page.waitForFunction(() => document.querySelector('[data-testid=machine-menu]')?.textContent?.includes('accelRig'), null, { timeout: 60_000 });
await phaseIs('ready');
await byId('tab-capture').click();
await byId('capture-kind').selectOption('sweep');
await byId('capture-from').fill('15');
await byId('capture-to').fill('40');
await byId('capture-rate').fill(String(25 / seconds));
await byId('capture-accel-per-hz').fill('60');
console.error(`[captureui] a ${seconds} s sweep on the accelRig`);

// The Long Tasks API over the whole capture (tasks over 50 ms, wall time), and a trace
// over its last 3 s: the end of the motion, the record's arrival and its first draw (a
// trace of a whole minute outgrows what node can read as one string).
await page.evaluate(() => {
  window.__longTasks = [];
  new PerformanceObserver((list) => list.getEntries().forEach((e) => window.__longTasks.push(e.duration))).observe({ type: 'longtask' });
});
await byId('capture-run').click();
await page.waitForFunction(() => {
  const p = document.querySelector('[data-testid=capture-progress] progress');
  return !p || Number(p.max) - Number(p.value) <= 3;
}, null, { timeout: 120_000 + seconds * 4000, polling: 100 });
await startTrace(browser, page, TRACE);
await byId('capture-peak').waitFor({ timeout: 120_000 + seconds * 4000 });
const capture = await stopTrace(browser);
const captureLongTasks = await page.evaluate(() => window.__longTasks.splice(0));
const samples = Number(await byId('capture-samples').getAttribute('data-value'));
const measured = page.locator('[data-testid=capture-plot] path[data-series^="measured"]');
const plotSamples = Number(await measured.getAttribute('data-samples'));
const plotPoints = Number(await measured.getAttribute('data-points'));

await startTrace(browser, page, TRACE);
const box = await byId('capture-plot').boundingBox();
await page.mouse.move(box.x + box.width * 0.55, box.y + box.height / 2);
for (let k = 0; k < 8; k++) await page.mouse.wheel(0, -300);
await page.mouse.move(box.x + box.width * 0.5, box.y + box.height / 2);
await page.waitForFunction(() => document.querySelector('[data-testid=capture-cursor]')?.textContent?.startsWith('t = '), null, { timeout: 30_000 });
const zoom = await stopTrace(browser);

await startTrace(browser, page, TRACE);
const t0 = Date.now();
const [download] = await Promise.all([page.waitForEvent('download', { timeout: 300_000 }), byId('capture-csv').click()]);
const path = await download.path();
const csvExportMs = Date.now() - t0;
const csv = await stopTrace(browser);
const rows = csvParse(await readFile(path, 'utf8'));
const span_s = (Number(rows[rows.length - 1].author_us) - Number(rows[0].author_us)) / 1e6;
await browser.close();

const figures = (t) => ({ longestTaskMs: Math.round(t.longest * 10) / 10, longestTaskCpuMs: Math.round(t.longestCpu * 10) / 10, over50: t.over50, tasks: t.tasks });
console.error(`[captureui] ${samples} samples; longest main-thread task: capturing ${capture.longest.toFixed(0)} ms (CPU ${capture.longestCpu.toFixed(0)}), zooming ${zoom.longest.toFixed(0)} ms, CSV ${csv.longest.toFixed(0)} ms; CSV in ${csvExportMs} ms`);
console.log(
  JSON.stringify({
    seconds,
    samples,
    sampleRateHz: Math.round(((rows.length - 1) / span_s) * 10) / 10,
    plotSamples,
    plotPoints,
    csvRows: rows.length,
    csvExportMs,
    capture: figures(capture),
    captureLongTasks: { over50: captureLongTasks.length, longestMs: captureLongTasks.length ? Math.round(Math.max(...captureLongTasks)) : 0 },
    zoom: figures(zoom),
    csv: figures(csv),
    targets: { longestTaskMs: 50 },
  }),
);
process.exit(0);
