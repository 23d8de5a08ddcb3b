/**
 * The draw bench's strokes in virtual time (no browser): the plotter's live drawer
 * (app/tools/plotter/live/liveDrawer.ts) on the simulated Blot (real firmware in
 * wasm, the plant's pen and ink) on a VirtualScheduler, fed by an exact pointer: a
 * point every SAMPLE_MS of virtual time, taken the moment it is made. What the
 * chromium run adds to this (a page, a worker, a paced clock, a busy machine) is
 * the difference between the two.
 */
import { startMachine } from '../core/system/harness.ts';
import { blotPlotter } from '../core/sim/presets/blotPlotter.ts';
import { LiveDrawer } from '../app/tools/plotter/live/liveDrawer.ts';
import { penDefaults, DEFAULT_TOLERANCE_MM } from '../app/tools/plotter/penDefaults.ts';
import type { DrawTruth } from '../app/tools/plotter/protocol.ts';
import { byLength, SAMPLE_MS, travelled, type StrokeSpec } from './drawStrokes.ts';

export async function drawVirtual(specs: readonly StrokeSpec[]): Promise<{ truth: Pick<DrawTruth, 'ink' | 'strokes' | 'lead_us' | 'limits' | 'tolerance_mm'>; fastSent: number; warnings: string[] }> {
  const preset = blotPlotter();
  const b = await startMachine(preset);
  const warnings: string[] = [];
  const drawer = new LiveDrawer({
    maxl: b.maxl,
    claim: () => true,
    release: () => {},
    log: (level, code, message) => {
      if (level !== 'info') warnings.push(`${code}: ${message}`);
    },
    strokeRefused: (id, reason) => warnings.push(`stroke ${id} refused: ${reason}`),
  });
  drawer.attach(b.maxl);
  const pen = penDefaults({ motionAxes: ['x', 'y'], eventChannels: ['pen'], limits: { maxVelocity: 120 } }, preset.id)!;
  const strokes: DrawTruth['strokes'] = [];
  let fastSent = 0;
  for (const [k, spec] of specs.entries()) {
    const { length, at } = byLength(spec.path);
    const first = at(0);
    const record = { id: k + 1, points: [first[0], first[1], b.scheduler.now()], arrived: [b.scheduler.now()], behindMax_mm: 0, waitingMax: 0 };
    drawer.start(record.id, first, pen, DEFAULT_TOLERANCE_MM);
    // Pressed at the first point until the tool rests there, then the pen-down delay and 100 ms.
    for (;;) {
      await b.scheduler.advance(1000);
      const e = b.maxl.estimate();
      if (e.speed === 0 && Math.hypot(e.position[0] - first[0], e.position[1] - first[1]) < 0.05 && b.maxl.queue.untransmittedCount === 0) break;
    }
    await b.scheduler.advance((pen.delayDown_s + 0.1) * 1e6);
    const t0 = b.scheduler.now();
    let sent = 1;
    for (;;) {
      await b.scheduler.advance(SAMPLE_MS * 1000);
      const t = b.scheduler.now();
      const s = travelled((t - t0) / 1e6, length, spec.speed);
      const p = at(s);
      drawer.points(record.id, p);
      sent++;
      record.points.push(p[0], p[1], t);
      record.arrived.push(t);
      const st = drawer.status();
      record.behindMax_mm = Math.max(record.behindMax_mm, st.behind_mm);
      record.waitingMax = Math.max(record.waitingMax, st.waitingMoves);
      if (s >= length) break;
    }
    drawer.end(record.id);
    if (spec.kind === 'fast') fastSent = sent;
    strokes.push(record);
    while (drawer.active) {
      await b.scheduler.advance(5000);
      drawer.settle();
    }
  }
  await b.scheduler.advance(50_000);
  b.sim.sync();
  const ink = (b.sim.plant.pen?.strokes ?? []).map((s) => s.x.flatMap((x, i) => [x, s.y[i], s.t_us[i]]));
  const truth = { ink, strokes, lead_us: b.maxl.lead_us, limits: { maxVelocity: 120, maxAcceleration: 1500 }, tolerance_mm: DEFAULT_TOLERANCE_MM };
  await b.maxl.end();
  await b.sim.stop();
  return { truth, fastSent, warnings };
}
