/**
 * The fault matrix (issue 11 §2): one job on a simulated machine (real firmware in
 * wasm, virtual time, seeded), one fault injected at a chosen moment, then the
 * recovery a user would make: wait for the stop, undo the fault (plug the cable
 * back in), reconnect(), resumeJob(), run to the job's end. Each case measures:
 *
 *   detection_ms      fault → the author's stop record (maxl.stopped), ms
 *   restSteady        once stopped, no motor steps for 200 ms (every reader at v = 0)
 *   offPathAtRest_mm  the carriage's distance from the job's path, at rest
 *   offPath_mm        the same, worst over the whole run (1 ms samples)
 *   worstBack_mm      worst step back along the path between two samples, beyond
 *                     the boards' spread (a rejoin): > 0 would mean path run twice
 *   lateSteps         worst excess of a motor over its plan, in steps, beyond one step
 *                     plus v·(clock-model error + 25 µs) (harness.ts), while the plan
 *                     is being followed (before the fault, after the resume): > 0
 *                     would mean a segment executed late or partially
 *   stateOk           maxl.stopped.reason is the fault's, and an error event said
 *                     "Streaming stopped" (the words the workbench shows); for a
 *                     stop after the job's end (endedBeforeStop), the words say it
 *                     "had already run to its end" and reconnect() finds nothing left
 *   endedBeforeStop   the job had run to its end before the author's stop: its last
 *                     segment's end time passed and the carriage stood at the job's
 *                     end point (≤ 0.02 mm) when the stop was recorded (a cut in the
 *                     job's last moments: the silence limit outlasts the job)
 *   resumed           the job ran to its end: nothing left queued, no stop pending
 *   endError_mm       the carriage's distance from the job's end point at the end:
 *                     a step's rounding (≤ 0.02) except after a board restarted, whose
 *                     position is the plan's at its last frame (v × time since it)
 */
import type { Move } from '../index.ts';
import { accelRig, blotPlotter, lightPainter, type MachinePreset } from '../sim/presets/index.ts';
import type { SimulatedMachineOptions } from '../sim/machine.ts';
import { modelError_us, motorTracks, planned, REFIT_US, settle, startMachine, type Bench } from './harness.ts';
import { PathTracker } from './pathTracker.ts';

export type PresetName = 'blotPlotter' | 'lightPainter' | 'accelRig';
export type FaultKind = 'cut' | 'corrupt' | 'latency' | 'reboot' | 'clockJump' | 'wrap';

export interface FaultCase {
  preset: PresetName;
  kind: FaultKind;
  seed: number;
  /** When the fault comes, as a fraction of the clean job's duration. */
  at: number;
  /** The device it hits (default: the preset's first). */
  device?: string;
  /** Byte corruption probability, both directions of every link (kind 'corrupt'). */
  corruption?: number;
  /** How far the device's µs counter jumps (kind 'clockJump'; default +50 000: ahead; < 0: back). */
  jump_us?: number;
}

export interface FaultOutcome {
  case: FaultCase;
  device: string;
  fault_ms: number;
  stops: number;
  reasons: string[];
  detection_ms: number | null;
  restSteady: boolean;
  offPathAtRest_mm: number;
  offPath_mm: number;
  worstBack_mm: number;
  spread_mm: number;
  lateSteps: number;
  boardSource: string[];
  stateOk: boolean;
  endedBeforeStop: boolean;
  resumed: boolean;
  endError_mm: number;
  resends: number;
  /** Planned positions every 5 ms from the job's start (compared across runs for corruption). */
  plan: number[][];
}

export const PRESETS: Record<PresetName, () => MachinePreset> = { blotPlotter, lightPainter, accelRig };

/** Each preset's job: corners and long straights, fast enough that braking takes a while. */
export const JOBS: Record<PresetName, number[][]> = {
  blotPlotter: [[10, 10], [90, 10], [90, 60], [30, 70], [30, 20], [80, 40]],
  lightPainter: [[20, 20], [150, 20], [150, 120], [40, 140], [60, 40], [200, 90]],
  accelRig: [[60], [10], [120], [30], [90]],
};

/** The author time at which a job crossing the u32 wrap sees its board's counter wrap (kind 'wrap'). */
const WRAP_AT_US = 3_200_000;
const WRAP = 2 ** 32;

const cleanDurations = new Map<PresetName, number>();

/** The clean job's duration on `preset` (µs, from its first move to rest), measured once. */
export async function jobDuration(preset: PresetName): Promise<number> {
  const known = cleanDurations.get(preset);
  if (known !== undefined) return known;
  const b = await startMachine(PRESETS[preset](), { seed: 1 });
  const t0 = b.scheduler.now();
  for (const p of JOBS[preset]) void b.maxl.addSegmentToQueue({ endPosition: p });
  await settle(b.scheduler, b.maxl.whenIdle(), 120_000_000);
  const d = b.scheduler.now() - t0;
  await b.maxl.end();
  await b.sim.stop();
  cleanDurations.set(preset, d);
  return d;
}

function simOptions(c: FaultCase, device: string): Partial<SimulatedMachineOptions> {
  if (c.kind === 'corrupt') {
    const p = c.corruption ?? 1e-3;
    const links = Object.fromEntries(PRESETS[c.preset]().devices.map((d) => [d.name, { toDevice: { corruptionProbability: p }, toAuthor: { corruptionProbability: p } }]));
    return { links };
  }
  if (c.kind === 'wrap') return { clocks: { [device]: { offset_us: WRAP - WRAP_AT_US, ppm: -25 } } };
  return {};
}

/** Injects the fault now; returns how to undo it once the machine stopped (null: nothing to undo). */
async function inject(b: Bench, c: FaultCase, device: string): Promise<(() => void) | null> {
  switch (c.kind) {
    case 'cut':
    case 'wrap':
      b.sim.cut(device);
      return () => b.sim.restore(device);
    case 'reboot':
      await b.sim.reboot(device);
      return null;
    case 'clockJump':
      b.sim.jumpClock(device, c.jump_us ?? 50_000);
      return null;
    case 'latency': {
      // Both directions 200 ms slower for 200 ms, then as before.
      const link = b.sim.simLinks[device].config;
      const down = link.toDevice.baseDelay_us;
      const up = link.toAuthor.baseDelay_us;
      b.sim.configureLink(device, 'toDevice', { baseDelay_us: down + 200_000 });
      b.sim.configureLink(device, 'toAuthor', { baseDelay_us: up + 200_000 });
      b.scheduler.after(200_000, () => {
        b.sim.configureLink(device, 'toDevice', { baseDelay_us: down });
        b.sim.configureLink(device, 'toAuthor', { baseDelay_us: up });
      });
      return null;
    }
    case 'corrupt':
      return null;
  }
}

const EXPECTED: Record<FaultKind, string[]> = {
  cut: ['lost'],
  wrap: ['lost'],
  reboot: ['rebooted'],
  clockJump: ['refused', 'lost'],
  latency: ['refused', 'lost'],
  corrupt: ['refused', 'lost'],
};

/** Faults the author must detect and report even after the job's end. */
const MUST_DETECT: FaultKind[] = ['cut', 'wrap', 'reboot'];
/** How long after such a fault the matrix waits for its stop (the silence limit is 300 ms). */
const DETECTION_WAIT_US = 2_000_000;

/** Runs one case of the matrix. */
export async function runFaultCase(c: FaultCase): Promise<FaultOutcome> {
  const duration = await jobDuration(c.preset);
  const preset = PRESETS[c.preset]();
  const device = c.device ?? preset.devices[0].name;
  const b = await startMachine(preset, { seed: c.seed, sim: simOptions(c, device) });
  const job = JOBS[c.preset];
  const start = [...b.maxl.queue.tailPosition];
  const axes = b.sim.config.motionAxes;
  const tracker = new PathTracker([start, ...job]);
  const motors = motorTracks(b).map((m) => ({ ...m, device: b.sim.preset.plant.motors.find((x) => x.name === m.motor)!.device }));
  const moves: Move[] = job.map((p) => ({ endPosition: p }));
  const t0 = b.scheduler.now();
  for (const m of moves) void b.maxl.addSegmentToQueue(m);
  let faultAt = t0 + c.at * duration;
  if (c.kind === 'wrap') faultAt = Math.max(faultAt, WRAP_AT_US + 100_000);
  if (c.kind === 'corrupt') faultAt = t0; // on from the start

  const out: FaultOutcome = {
    case: c,
    device,
    fault_ms: (faultAt - t0) / 1000,
    stops: 0,
    reasons: [],
    detection_ms: null,
    restSteady: true,
    offPathAtRest_mm: 0,
    offPath_mm: 0,
    worstBack_mm: 0,
    spread_mm: 0,
    lateSteps: -Infinity,
    boardSource: [],
    stateOk: true,
    endedBeforeStop: false,
    resumed: false,
    endError_mm: Infinity,
    resends: 0,
    plan: [],
  };
  let injected = c.kind === 'corrupt';
  // Plan following is checked from here (Infinity: not now): from the job's first
  // transmission on. Before it the author's record is empty and its plan reads the
  // queue's tail, the job's end: nothing the motors could follow yet (they stand
  // still; offPath_mm covers them).
  let checkFrom = Infinity;
  let resuming = false;
  let firstStart = NaN;
  b.maxl.queue.subscribe((e) => {
    if (e.type !== 'transmitted') return;
    if (Number.isNaN(firstStart)) {
      firstStart = e.segments[0].startTime_us;
      if (!injected || c.kind === 'corrupt') checkFrom = t0;
    }
    // After a resume, from the first segment of the job itself (a rejoin has move id 0).
    const own = e.segments.find((s) => s.moveId !== 0);
    if (resuming && own) {
      checkFrom = own.startTime_us;
      resuming = false;
    }
  });
  const carriage = () => {
    const c2 = b.sim.plant.carriage();
    return axes.map((a) => c2[a]);
  };
  const sample = () => {
    b.sim.sync();
    const t = b.scheduler.now();
    out.offPath_mm = Math.max(out.offPath_mm, tracker.add(carriage()));
    if (t >= checkFrom) {
      const steps = b.sim.plant.motorSteps();
      for (const m of motors) {
        const error = Math.abs(steps[m.motor] / m.stepsPerMm - planned(b, m.track, t)) * m.stepsPerMm;
        const v = Math.abs(planned(b, m.track, t + 50) - planned(b, m.track, t - 50)) / 100e-6;
        const bound = 1 + v * (Math.abs(modelError_us(b, m.device, t)) + REFIT_US) * 1e-6 * m.stepsPerMm;
        out.lateSteps = Math.max(out.lateSteps, error - bound);
      }
    }
  };
  const goal = job[job.length - 1];
  const limit = t0 + 20 * duration + 60_000_000;
  let undo: (() => void) | null = null;
  for (;;) {
    await b.scheduler.advance(1000);
    const now = b.scheduler.now();
    if (!injected && now >= faultAt) {
      faultAt = now;
      undo = await inject(b, c, device);
      injected = true;
      checkFrom = Infinity; // the fault itself takes the machine off its plan
    }
    sample();
    const stop = b.maxl.stopped;
    if (stop) {
      checkFrom = Infinity;
      out.stops++;
      out.reasons.push(stop.reason);
      if (out.detection_ms === null) out.detection_ms = (stop.at_us - faultAt) / 1000;
      if (!EXPECTED[c.kind].includes(stop.reason)) out.stateOk = false;
      const q = b.maxl.queue;
      const ended = q.untransmittedCount === 0 && q.transmittedEnd_us <= stop.at_us && Math.hypot(...carriage().map((v, i) => v - goal[i])) <= 0.02;
      if (ended) out.endedBeforeStop = true;
      // Brake, settle, then check the rest: 600 ms, then no step for 200 ms.
      for (let k = 0; k < 600; k++) {
        await b.scheduler.advance(1000);
        sample();
      }
      const steps = JSON.stringify(b.sim.plant.motorSteps());
      for (let k = 0; k < 200; k++) {
        await b.scheduler.advance(1000);
        sample();
      }
      if (JSON.stringify(b.sim.plant.motorSteps()) !== steps) out.restSteady = false;
      out.offPathAtRest_mm = Math.max(out.offPathAtRest_mm, tracker.add(carriage()));
      const words = ended ? 'had already run to its end' : 'Streaming stopped';
      if (!b.events.some((e) => e.type === 'error' && e.at >= stop.at_us - 1000 && e.text.includes(words))) out.stateOk = false;
      undo?.();
      undo = null;
      const report = await reconnect(b);
      if (ended && report.remaining !== 0) out.stateOk = false;
      out.spread_mm = Math.max(out.spread_mm, report.spread_mm);
      out.boardSource.push(...report.boards.map((x) => x.source));
      resuming = true;
      b.maxl.resumeJob();
      if (out.stops >= 5) break;
      continue;
    }
    const q = b.maxl.queue;
    const planEnded = q.untransmittedCount === 0 && q.transmittedEnd_us < now - 50_000;
    // A cut or a restart must be detected even when the job ends before the silence
    // limit runs out (a cut in its last moments): wait for the stop that long.
    const detectionDue = MUST_DETECT.includes(c.kind) && out.stops === 0 && now < faultAt + DETECTION_WAIT_US;
    if (planEnded && now > faultAt && !detectionDue) break;
    if (now > limit) break;
  }
  for (let k = 0; k < 50; k++) {
    await b.scheduler.advance(1000);
    sample();
  }
  const end = carriage();
  out.endError_mm = Math.hypot(...end.map((v, i) => v - goal[i]));
  out.resumed = b.maxl.stopped === null && b.maxl.queue.untransmittedCount === 0 && b.maxl.queue.transmittedEnd_us < b.scheduler.now();
  out.worstBack_mm = Math.max(0, tracker.worstBack - out.spread_mm);
  out.resends = (b.maxl as unknown as { runtime: { sessions: Array<{ resends: number }> } }).runtime.sessions.reduce((n, s) => n + s.resends, 0);
  if (!Number.isNaN(firstStart)) for (let t = firstStart; t <= firstStart + duration; t += 5000) out.plan.push(b.maxl.sample(t).position);
  if (out.lateSteps === -Infinity) out.lateSteps = 0;
  await b.maxl.end();
  await b.sim.stop();
  return out;
}

/** reconnect(), tried up to 5 times (a corrupted link may lose a hello or a status). */
async function reconnect(b: Bench) {
  let last: unknown;
  for (let attempt = 0; attempt < 5; attempt++) {
    try {
      return await settle(b.scheduler, b.maxl.reconnect(), 10_000_000);
    } catch (err) {
      last = err;
    }
  }
  throw last;
}
