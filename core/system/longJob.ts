/**
 * A long job with bounded drift: one board whose crystal runs 150 ppm fast, its
 * µs counter wrapping every 71.6 minutes, drawing a stroke every `every_us` for
 * `duration_us` (idle in between, pinging as a session does). What must stay
 * bounded over the hours is the author's model of the board's clock, and with it
 * how closely each stroke follows its plan:
 *
 *   worstModelError_us   worst |model − true device clock| 10 ms ahead (harness.ts
 *                        modelError_us), sampled every second and after each stroke
 *   settledModelError_us the same from one minute after begin() on (the model young
 *                        at first; the drift it must follow after that)
 *   worstLateSteps       worst excess of a motor over its plan beyond one step plus
 *                        v·(model error + 25 µs), over every stroke (≤ 0 passes)
 *   lastStrokeSteps      worst plain error (steps) during the last stroke
 *   modelErrorPerHour_us the worst model error in each hour of the job (bounded: no growth)
 *   wraps                times the board's counter wrapped during the job
 */
import { blotPlotter } from '../sim/presets/index.ts';
import { modelError_us, runAndCheckPositions, startMachine } from './harness.ts';

export interface LongJobOutcome {
  hours: number;
  strokes: number;
  wraps: number;
  worstModelError_us: number;
  settledModelError_us: number;
  modelErrorPerHour_us: number[];
  worstLateSteps: number;
  lastStrokeSteps: number;
  errors: string[];
}

const STROKE = [[40, 10], [60, 40], [20, 50], [10, 10]];

export async function runLongJob(duration_us: number, every_us = 60_000_000, seed = 8): Promise<LongJobOutcome> {
  // The counter wraps 30 s in, and every 71.6 min after.
  const b = await startMachine(blotPlotter(), { seed, sim: { clocks: { blot: { offset_us: 2 ** 32 - 30_000_000, ppm: 150 } } } });
  const clock = b.sim.devices.blot.clock;
  const t0 = b.scheduler.now();
  const out: LongJobOutcome = { hours: 0, strokes: 0, wraps: 0, worstModelError_us: 0, settledModelError_us: 0, modelErrorPerHour_us: [], worstLateSteps: -Infinity, lastStrokeSteps: 0, errors: [] };
  let lastMicros = clock.microsAt(t0);
  const watchClock = () => {
    const t = b.scheduler.now();
    const m = clock.microsAt(t);
    if (m < lastMicros) out.wraps++;
    lastMicros = m;
    const e = Math.abs(modelError_us(b, 'blot', t + 10_000));
    out.worstModelError_us = Math.max(out.worstModelError_us, e);
    if (t - t0 > 60_000_000) out.settledModelError_us = Math.max(out.settledModelError_us, e);
    const hour = Math.floor((t - t0) / 3.6e9);
    out.modelErrorPerHour_us[hour] = Math.max(out.modelErrorPerHour_us[hour] ?? 0, e);
  };
  while (b.scheduler.now() - t0 < duration_us) {
    const check = await runAndCheckPositions(
      b,
      STROKE.map((p) => ({ endPosition: p })),
    );
    out.strokes++;
    out.worstLateSteps = Math.max(out.worstLateSteps, check.worstExcess);
    out.lastStrokeSteps = check.worstSteps;
    watchClock();
    const next = t0 + out.strokes * every_us;
    while (b.scheduler.now() < next) {
      await b.scheduler.advance(Math.min(1_000_000, next - b.scheduler.now()));
      watchClock();
    }
  }
  out.hours = (b.scheduler.now() - t0) / 3.6e9;
  out.errors = b.events.filter((e) => e.type === 'error').map((e) => e.text);
  await b.maxl.end();
  await b.sim.stop();
  return out;
}
