/**
 * `npm run bench -- draw`: live drawing in Debian's chromium, on the simulated Blot
 * plotter (paced simulator: real firmware in wasm, the plant's pen and ink), with a
 * scripted pointer (Playwright's page.mouse, real input events) on the Plotter tab.
 *
 * The strokes (machine mm; the Blot's bed is 0–125 mm, 120 mm/s, 1 500 mm/s²):
 *   smooth  three curves at 50 mm/s whose radius of curvature is ≥ 5 mm everywhere:
 *           a circle (r 20), a sine wave (amplitude 6, wavelength 45: r ≥ 8.5), a
 *           spiral (r 8 → 20)
 *   zigzag  five 14 mm legs with right-angle corners at 50 mm/s
 *   fast    a circle (r 18) at 150 mm/s, above the machine's 120 mm/s
 * The pointer moves as a hand does: it presses at the stroke's first point and
 * waits there until the machine has travelled to it and the pen has landed (the
 * simulated pen's first ink of the stroke reaches the page), and 100 ms more. (It
 * waited for the tool at rest on the point and the pen-down delay before, which
 * the first stroke passed too early: the tool may rest on the point before its
 * pen-up dwell, so the pointer moved ~0.5 s before the pen touched.) It speeds up to the
 * stroke's speed and slows to rest at its end at POINTER_ACCEL (below the
 * machine's acceleration, so the ends do not ask more than the middle), and lifts.
 * A move goes out every SAMPLE_MS of wall time (as the page's timers allow), at the
 * position the path has then (see POINTER_SCRIPT).
 * Each stroke ends (the plotter idle) before the next starts.
 *
 * Time: every pointer event is stamped by the page (event.timeStamp, on the page's
 * performance clock). The page sends performance.timeOrigin + timeStamp (epoch ms);
 * the worker subtracts its own performance.timeOrigin to get the wall time on its
 * performance.now() scale, and PacedScheduler.virtualTimeAtWall() turns that into
 * author µs: the paced simulator's virtual time is the wall time less a fixed
 * offset (it runs every timer at its exact virtual time as the wall clock reaches
 * it). The simulated pen stamps its ink with author µs too. The dev/test hook
 * (docs/test-hooks.md) returns both.
 *
 * Figures:
 *   toolLagMs {p50, p99, max}  over every pointer point of the smooth curves (after
 *                   the first, where the pointer waits): from the pointer passing the
 *                   point (its event's time) to the simulated tool passing it (the
 *                   time of the ink's nearest approach to the point, interpolated
 *                   between the pen's 1 ms samples, searched forward along the ink)
 *   lagFloorMs      the floor of that lag: brakeMs + leadMs + samplingMs, where
 *                   brakeMs = v/(2a) (a tool that can always stop at the last point it
 *                   knows stays a braking distance v²/(2a) behind: at speed v, that is
 *                   v/(2a) of time), leadMs = the streamer's lead (minimal buffering
 *                   keeps it transmitted ahead: 2·RTT + margin), samplingMs = the mean
 *                   interval between the pointer points kept by thinning (a point
 *                   cannot be planned before it arrives)
 *   stopsInsideStrokes  times the tool came to rest inside a smooth curve: gaps of over
 *                   5 ms between ink samples (the pen adds a sample only when the tool
 *                   moved ≥ 0.01 mm in 1 ms: slower than 2 mm/s for 5 ms is at rest),
 *                   between the tool passing the curve's second point and its
 *                   second-to-last
 *   stopCauses      for each of those rests: when (ms into the stroke), and the pointer's
 *                   largest gap between points and slowest arrival (pointArrivalMs) in
 *                   the 100 ms before it: a rest after a pointer that paused is the
 *                   input's, not the planner's
 *   inkErrorMm      Hausdorff distance between all strokes (the pointer points the
 *                   worker received, as polylines) and all the ink
 *   pointsDropped   for the fast stroke: points the page sent that the worker did not
 *                   receive, plus received points farther than 0.3 mm from its ink
 *   fastStroke.behindMaxMm, .waitingMax  how far the machine fell behind the fast
 *                   stroke, and the most moves that waited in the tool for room
 *   pointerWorstGapMs  the longest interval between two pointer moves (the page's
 *                   main thread shares 2 cores with everything else here)
 *   pointArrivalMs  from a pointer event to the worker's drawer taking its point, on
 *                   the author's clock: the page → worker message's latency, part of
 *                   the lag. Never negative: when the paced simulator trails the wall
 *                   clock (its worker starved), a point stamped ahead of the author's
 *                   clock waits until the clock reaches its stamp
 *                   (app/tools/plotter/live/pointerTimeline.ts), so the machine never
 *                   knows a point before the pen made it
 *   simulatorStalls  the paced simulator's wakes, while a stroke was drawn, that fired
 *                   over 5 ms after their timer was due (worstLateMs: the worker's
 *                   thread was busy or descheduled) or ran over 5 ms of timers
 *                   (worstRunMs: the simulation itself was slow): core/time/
 *                   pacedScheduler.ts PacingStall
 *   timingValid     whether the scripted pointer kept its pace (worst gap ≤ 3
 *                   samples); when false, the lag and stop figures measure a pointer
 *                   that paused (the page's thread was descheduled), not live drawing
 *                   (loadAverage says how busy the machine was)
 * Targets: toolLagMs.p99 ≤ lagFloorMs + 5; stopsInsideStrokes = 0; inkErrorMm ≤ 0.3;
 * pointsDropped = 0.
 *
 *   virtualTime     the same figures for the same strokes drawn by an exact pointer on
 *                   the simulated Blot in virtual time (bench/drawVirtual.ts): live
 *                   drawing without the page, the worker and a busy machine
 * The strokes and the pointer's motion: bench/drawStrokes.ts; the figures:
 * bench/drawFigures.ts.
 *
 * Options: --port N (vite, default 5185); DRAW_BENCH_DUMP=file writes the hook's truth
 * there. Prints one JSON object as its last line.
 */
import { chromium, type Page } from '@playwright/test';
import { spawn } from 'node:child_process';
import { writeFileSync } from 'node:fs';
import { loadavg } from 'node:os';
import { setTimeout as delay } from 'node:timers/promises';
import type { DrawTruth } from '../app/tools/plotter/protocol.ts';
import { drawFigures, round } from './drawFigures.ts';
import { byLength, POINTER_ACCEL, SAMPLE_MS, STROKES, type StrokeSpec } from './drawStrokes.ts';
import { drawVirtual } from './drawVirtual.ts';

const args = process.argv.slice(2);
const PORT = args.includes('--port') ? Number(args[args.indexOf('--port') + 1]) : 5185;
const URL_ = `http://localhost:${PORT}/`;
const ARGS = ['--no-sandbox', '--disable-gpu', '--disable-background-networking', '--disable-component-update', '--disable-sync'];

// --- the page ---

const server = spawn('npx', ['vite', '--port', String(PORT), '--strictPort'], { env: { ...process.env, MAXL_NO_HMR: '1' }, stdio: 'ignore', detached: true });
const stopServer = () => {
  try {
    process.kill(-(server.pid as number), 'SIGTERM');
  } catch {
    // already gone
  }
};
process.on('exit', stopServer);

async function waitForServer(): Promise<void> {
  for (let i = 0; i < 300; i++) {
    try {
      if ((await fetch(URL_)).ok) return;
    } catch {
      // not yet
    }
    await delay(100);
  }
  throw new Error(`vite did not start on ${URL_}`);
}

interface Hook {
  maxlWorkbench: { plotter: { truth(): Promise<DrawTruth>; strokes: Array<{ id: number; xy: number[] }> } };
}

/** Machine mm → px relative to the bed's canvas (BedView publishes its mapping on it). */
async function bedMapping(page: Page): Promise<(p: [number, number]) => [number, number]> {
  const bed = page.getByTestId('plotter-bed');
  const attr = async (name: string) => Number(await bed.getAttribute(name));
  const [scale, ox, oy, minX, minY] = [await attr('data-scale'), await attr('data-ox'), await attr('data-oy'), await attr('data-min-x'), await attr('data-min-y')];
  return ([x, y]) => [ox + (x - minX) * scale, oy + (y - minY) * scale];
}

/**
 * The scripted pointer runs inside the page: a move every SAMPLE_MS at the position
 * the path has at that wall time, dispatched as a PointerEvent (pointerType "pen")
 * to the bed's canvas, through the same handlers as a real pen. While a stroke is
 * drawn it holds the page's main thread and waits for each sample time by reading
 * the clock (the page does not paint meanwhile; the worker, which runs the
 * simulated machine, is another thread): on this shared 2-core machine the page's
 * timers fire tens of ms late, and page.mouse (the browser's input pipeline, as
 * the e2e spec uses) waits a frame per move, ~33 ms at best. Either would make a
 * 125 Hz pointer a 15–30 Hz one.
 */
const POINTER_SCRIPT = `
window.__drawPointer = (a) => new Promise((resolve) => {
  const canvas = document.querySelector('[data-testid=plotter-bed]');
  const r = canvas.getBoundingClientRect();
  const fire = (type, i) => canvas.dispatchEvent(new PointerEvent(type, { pointerId: 17, pointerType: 'pen', isPrimary: true, bubbles: true, cancelable: true, button: 0, buttons: type === 'pointerup' ? 0 : 1, clientX: r.left + a.px[2 * i], clientY: r.top + a.px[2 * i + 1] }));
  const n = a.px.length / 2 - 1;
  const ta = a.speed / a.accel, da = 0.5 * a.accel * ta * ta, cruise = (a.length - 2 * da) / a.speed;
  const along = (t) => t <= ta ? 0.5 * a.accel * t * t : t <= ta + cruise ? da + a.speed * (t - ta) : t - ta - cruise >= ta ? a.length : a.length - 0.5 * a.accel * (2 * ta + cruise - t) ** 2;
  // The pen has landed when its first ink of this stroke reaches the page (the
  // simulated pen lays ink only once it touches: the travel, the pen-up and pen-down
  // dwells come first); a hand waits for that, and 100 ms more.
  const plotter = window.maxlWorkbench.plotter;
  const inkBefore = plotter.ink.length;
  fire('pointerdown', 0);
  const waitForPen = () => {
    if (plotter.ink.length > inkBefore) setTimeout(draw, 100);
    else setTimeout(waitForPen, 10);
  };
  const draw = () => {
    const t0 = performance.now();
    let moves = 0, worstGap = 0, last = t0, next = t0 + a.sample;
    for (;;) {
      while (performance.now() < next) {}
      // A sample time missed (the page was descheduled) is skipped, not caught up in a burst.
      next = Math.max(next + a.sample, performance.now() + a.sample / 2);
      const now = performance.now();
      worstGap = Math.max(worstGap, now - last);
      last = now;
      const s = along((now - t0) / 1000);
      fire('pointermove', Math.min(n, Math.round(s / a.step)));
      moves++;
      if (s >= a.length) break;
    }
    fire('pointerup', n);
    resolve({ moves, worstGap, seconds: (performance.now() - t0) / 1000 });
  };
  waitForPen();
});
`;

/** Positions along the stroke every STEP_MM, in px relative to the canvas. */
const STEP_MM = 0.02;

interface Drawn {
  moves: number;
  /** ms, the longest interval between two pointer moves. */
  worstGap: number;
  seconds: number;
}

async function drawStroke(page: Page, toCanvasPx: (p: [number, number]) => [number, number], spec: StrokeSpec): Promise<Drawn> {
  const { length, at } = byLength(spec.path);
  const px: number[] = [];
  for (let k = 0; k * STEP_MM <= length + 1e-9; k++) px.push(...toCanvasPx(at(k * STEP_MM)));
  px.push(...toCanvasPx(at(length)));
  const r = await page.evaluate((a) => (window as unknown as { __drawPointer(a: unknown): Promise<Drawn> }).__drawPointer(a), {
    px,
    step: STEP_MM,
    length,
    speed: spec.speed,
    accel: POINTER_ACCEL,
    sample: SAMPLE_MS,
  });
  await page.waitForFunction(() => document.querySelector('[data-testid=plotter-status]')?.getAttribute('data-active') === 'false', null, { timeout: 60_000 });
  return r;
}

await waitForServer();
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM_PATH ?? '/usr/bin/chromium', args: ARGS });
const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
page.on('pageerror', (e) => console.error(`[page error] ${e.message}`));
await page.goto(URL_);
await page.waitForFunction(() => document.querySelector('[data-testid=phase]')?.textContent === 'ready', null, { timeout: 60_000 });
await page.getByTestId('machine-menu').click();
await page.getByTestId('preset-blotPlotter').click();
await page.waitForFunction(() => [...document.querySelectorAll('[data-testid=log-entry][data-code=READY]')].some((e) => e.textContent?.includes('blot')), null, { timeout: 60_000 });
await page.waitForFunction(() => document.querySelector('[data-testid=phase]')?.textContent === 'ready', null, { timeout: 60_000 });
await page.getByTestId('tab-plotter').click();
await page.getByTestId('plotter-clear').click();
const toPx = await bedMapping(page);
await page.addScriptTag({ content: POINTER_SCRIPT });
console.error('[draw] the simulated Blot is ready; drawing');

let worstGapMs = 0;
for (const spec of STROKES) {
  const r = await drawStroke(page, toPx, spec);
  worstGapMs = Math.max(worstGapMs, r.worstGap);
  console.error(`[draw] ${spec.name} drawn: ${r.moves} pointer moves in ${r.seconds.toFixed(2)} s, the longest gap ${r.worstGap.toFixed(1)} ms`);
}
const truth = await page.evaluate(() => (window as unknown as Hook).maxlWorkbench.plotter.truth());
const sent = await page.evaluate(() => (window as unknown as Hook).maxlWorkbench.plotter.strokes.map((s) => ({ id: s.id, points: s.xy.length / 2 })));
const errors = await page.evaluate(() => [...document.querySelectorAll('[data-testid=log-entry]')].filter((e) => e.classList.contains('error') || e.classList.contains('warning')).map((e) => e.textContent?.trim()));
await browser.close();
stopServer();

if (process.env.DRAW_BENCH_DUMP) writeFileSync(process.env.DRAW_BENCH_DUMP, JSON.stringify(truth));
if (!truth.paced) throw new Error('the scheduler is not paced: pointer times cannot be mapped exactly');
if (truth.strokes.length !== STROKES.length || truth.ink.length !== STROKES.length) {
  throw new Error(`expected ${STROKES.length} strokes and as many inked, got ${truth.strokes.length} received and ${truth.ink.length} inked (log: ${errors.join(' | ')})`);
}

const chromiumFigures = drawFigures(truth, STROKES, sent.find((x) => x.id === truth.strokes[STROKES.findIndex((k) => k.kind === 'fast')].id)?.points ?? NaN);
// The paced simulator's wakes that came late or ran long while a stroke was drawn
// (from its first point to 100 ms after its last): virtual time stood still then.
const windows = truth.strokes.map((st) => [st.points[2], st.points[st.points.length - 1] + 100_000]);
const inStrokes = truth.stalls.filter((x) => windows.some(([a, b]) => x.at_us >= a && x.at_us <= b));
const simulatorStalls = {
  count: inStrokes.length,
  worstLateMs: round(Math.max(0, ...inStrokes.map((x) => x.late_ms))),
  worstRunMs: round(Math.max(0, ...inStrokes.map((x) => x.run_ms))),
};
const timingValid = worstGapMs <= 3 * SAMPLE_MS;
console.error('[draw] the same strokes in virtual time');
const virtual = await drawVirtual(STROKES);
const virtualFigures = drawFigures(virtual.truth, STROKES, virtual.fastSent);
const { pointArrivalMs: _exact, ...virtualTime } = virtualFigures;
void _exact;

const result = {
  bench: 'draw',
  ...chromiumFigures,
  pointerWorstGapMs: round(worstGapMs),
  simulatorStalls,
  // The chromium timing figures mean what they say only if the pointer kept its pace
  // (pointerWorstGapMs).
  timingValid,
  loadAverage: round(loadavg()[0]),
  logWarnings: errors.length,
  // The same strokes with an exact pointer in virtual time (bench/drawVirtual.ts).
  virtualTime,
  virtualWarnings: virtual.warnings.length,
};
if (errors.length) console.error(`[draw] log warnings: ${errors.join(' | ')}`);
if (virtual.warnings.length) console.error(`[draw] virtual-time warnings: ${virtual.warnings.join(' | ')}`);
console.log(JSON.stringify(result));
process.exit(0);
