// The page's main-thread tasks from a Chromium trace, for the benches that drive the
// workbench in chromium (ui.mjs, captureui.mjs).
/**
 * The page's main-thread tasks from a Chromium trace: every task of any length
 * ('toplevel' ThreadControllerImpl::RunTask on the renderer's CrRendererMain thread;
 * a nested task is shorter than the one around it, so the longest is a top one).
 */
export const startTrace = (browser, page, categories = ['toplevel', '__metadata', 'gpu']) => browser.startTracing(page, { categories });

/** Stops the trace and reads the main thread's tasks from it. */
export async function stopTrace(browser) {
  const trace = JSON.parse((await browser.stopTracing()).toString());
  const events = trace.traceEvents ?? trace;
  const main = new Set(events.filter((e) => e.name === 'thread_name' && e.args?.name === 'CrRendererMain').map((e) => `${e.pid}/${e.tid}`));
  // Top-level tasks only (one inside another, in a nested run loop, is part of it), in time order per thread.
  const all = events.filter((e) => e.ph === 'X' && e.name === 'ThreadControllerImpl::RunTask' && main.has(`${e.pid}/${e.tid}`)).sort((x, y) => x.ts - y.ts);
  const ends = new Map();
  const tasks = [];
  for (const e of all) {
    const thread = `${e.pid}/${e.tid}`;
    if (e.ts < (ends.get(thread) ?? -Infinity)) continue;
    ends.set(thread, e.ts + e.dur);
    tasks.push({ wall: e.dur / 1000, cpu: (e.tdur ?? NaN) / 1000 });
  }
  if (tasks.length === 0) throw new Error('the trace holds no main-thread task: is the trace category right for this chromium?');
  const readbacks = events.filter((e) => e.ph === 'X' && e.name === 'GLES2::ReadPixels' && main.has(`${e.pid}/${e.tid}`)).map((e) => e.dur / 1000);
  return {
    readbacks: readbacks.length,
    longestReadback: readbacks.length ? Math.max(...readbacks) : 0,
    longest: Math.max(...tasks.map((t) => t.wall)),
    // A task the trace gives no thread time (rare: one cut by the trace's start) is left out of these two.
    longestCpu: Math.max(...tasks.map((t) => t.cpu).filter(Number.isFinite)),
    cpuTotal: tasks.reduce((sum, t) => sum + (Number.isFinite(t.cpu) ? t.cpu : 0), 0),
    over50: tasks.filter((t) => t.wall > 50).length,
    tasks: tasks.length,
  };
}
