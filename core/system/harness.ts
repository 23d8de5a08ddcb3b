/**
 * Test harness: a real MAXL author talking to a simulated machine (real firmware
 * in wasm, simulated links and plant), all in deterministic virtual time.
 */
import { createMAXL, type Maxl, type MaxlOptions, type Move } from '../index.ts';
import { VirtualScheduler } from '../time/virtualScheduler.ts';
import { createSimulatedMachine, type SimulatedMachine, type SimulatedMachineOptions } from '../sim/machine.ts';
import { nodeWasmLoader } from '../sim/device/nodeWasmLoader.ts';
import type { MachinePreset } from '../sim/presets/index.ts';
import type { DeviceInfo } from '../net/session.ts';
import type { Link } from '../net/link.ts';
import { distanceToPolyline } from './geometry.ts';

export interface Bench {
  scheduler: VirtualScheduler;
  sim: SimulatedMachine;
  maxl: Maxl;
  devices: DeviceInfo[];
  /** runtime events seen, in order */
  events: Array<{ at: number; type: string; text: string }>;
}

export async function startMachine(
  preset: MachinePreset,
  options: {
    seed?: number;
    sim?: Partial<SimulatedMachineOptions>;
    maxl?: Partial<MaxlOptions>;
    start_us?: number;
    /** Wraps each of the simulator's links before the author gets it (to watch the bytes). */
    wrapLink?: (link: Link) => Link;
  } = {},
): Promise<Bench> {
  const scheduler = new VirtualScheduler(options.start_us ?? 0);
  const sim = await createSimulatedMachine(preset, scheduler, { seed: options.seed ?? 1, loader: nodeWasmLoader(), ...options.sim });
  const wrap = options.wrapLink ?? ((l: Link) => l);
  const maxl = createMAXL(sim.config, { links: Object.values(sim.links).map(wrap), scheduler, ...options.maxl });
  const events: Bench['events'] = [];
  maxl.on((e) => {
    if (e.type === 'samples') return;
    events.push({ at: scheduler.now(), type: e.type, text: 'error' in e ? e.error.message : JSON.stringify(e) });
  });
  const devices = await settle(scheduler, maxl.begin(), 5_000_000);
  return { scheduler, sim, maxl, devices, events };
}

/** Runs virtual time until `promise` settles (or fails after `limit_us`), and returns its value. */
export async function settle<T>(scheduler: VirtualScheduler, promise: Promise<T>, limit_us: number): Promise<T> {
  let done = false;
  let value: T | undefined;
  let error: unknown;
  promise.then(
    (v) => ((done = true), (value = v)),
    (e) => ((done = true), (error = e)),
  );
  await scheduler.runWhile(() => !done, scheduler.now() + limit_us);
  if (!done) throw new Error(`still waiting after ${limit_us / 1e6} s of virtual time`);
  if (error !== undefined) throw error;
  return value as T;
}

/**
 * After a stop: lets the machine brake for 3 s of virtual time, then watches it
 * 0.5 s more. Returns where the carriage rests, how far that is from `path` (a
 * polyline in the machine's first two axes, mm), and whether any motor stepped
 * while watched (it must not: at rest means still).
 */
export async function restingPlace(b: Bench, path: number[][]): Promise<{ carriage: Record<string, number>; offPath_mm: number; movedWhileWatched: boolean }> {
  await b.scheduler.advance(3_000_000);
  b.sim.sync();
  const steps = JSON.stringify(b.sim.plant.motorSteps());
  await b.scheduler.advance(500_000);
  b.sim.sync();
  const carriage = b.sim.plant.carriage();
  return { carriage, offPath_mm: distanceToPolyline([carriage.x, carriage.y], path), movedWhileWatched: JSON.stringify(b.sim.plant.motorSteps()) !== steps };
}

/**
 * Queues moves as a Listing 2 loop would, and calls `watch` every `every_us` of
 * virtual time (after syncing the plant) until the machine is idle.
 */
export async function runJob(b: Bench, moves: Move[], watch?: (t_us: number) => void, every_us = 1000, limit_us = 60_000_000): Promise<void> {
  const feeding = (async () => {
    for (const m of moves) await b.maxl.addSegmentToQueue(m);
  })();
  await b.scheduler.advance(0);
  const end = b.scheduler.now() + limit_us;
  let fed = false;
  void feeding.then(() => (fed = true));
  for (;;) {
    await b.scheduler.advance(every_us);
    b.sim.sync();
    watch?.(b.scheduler.now());
    if (fed && b.maxl.queue.untransmittedCount === 0 && b.maxl.queue.transmittedEnd_us < b.scheduler.now() - 2000) break;
    if (b.scheduler.now() > end) throw new Error('job did not finish');
  }
  await feeding;
}

/** For each plant motor: its steps/mm and the track its reader follows. */
export function motorTracks(b: Bench): Array<{ motor: string; track: string; stepsPerMm: number }> {
  return b.sim.preset.plant.motors.map((m) => {
    // A board with one stepper calls its reader anything; a board with several names them after the motors.
    const readers = b.sim.preset.devices.find((d) => d.name === m.device)?.readers.filter((r) => r.kind === 'position') ?? [];
    const reader = readers.length === 1 ? readers[0] : readers.find((r) => r.name === m.name);
    const sub = b.sim.config.subscriptions?.find((s) => s.device === m.device && s.reader === reader?.name);
    if (!sub) throw new Error(`no subscription drives motor ${m.name}`);
    return { motor: m.name, track: sub.track, stepsPerMm: m.stepsPerMm };
  });
}

/** A track's planned value at author time t. */
export function planned(b: Bench, track: string, t_us: number): number {
  return b.maxl.trackValue(track, t_us);
}

/** The author's clock model of a device, minus that device's true clock, at author time t (µs). */
export function modelError_us(b: Bench, device: string, t: number): number {
  const session = (b.maxl as unknown as { runtime: { sessions: Array<{ info: { name: string }; clock: { clock: { toDeviceExact(t: number): number } } }> } }).runtime.sessions.find(
    (s) => s.info.name === device,
  );
  if (!session) throw new Error(`no session with ${device}`);
  return session.clock.clock.toDeviceExact(t) - b.sim.devices[device].clock.deviceTimeAt(t);
}

/** µs allowed for the clock model being refitted between a segment's transmission and its execution. */
export const REFIT_US = 25;

/**
 * Runs a job and checks, every 0.25 ms, each motor's executed position against the
 * plan: within one step plus v·(|model error| + REFIT_US), the model error read from
 * the simulator's true clock (see positions.test.ts). Returns the worst excess over
 * that bound (≤ 0 passes), the worst error in plain steps, and sample counts.
 */
export async function runAndCheckPositions(b: Bench, moves: Move[]): Promise<{ worstExcess: number; worstSteps: number; samples: number; moving: number }> {
  const motors = motorTracks(b).map((m) => ({ ...m, device: b.sim.preset.plant.motors.find((x) => x.name === m.motor)!.device }));
  let worstExcess = -Infinity;
  let worstSteps = 0;
  let samples = 0;
  let moving = 0;
  await runJob(
    b,
    moves,
    (t) => {
      const steps = b.sim.plant.motorSteps();
      for (const m of motors) {
        const error = Math.abs(steps[m.motor] / m.stepsPerMm - planned(b, m.track, t)) * m.stepsPerMm;
        // The track's speed, by finite difference of the plan.
        const v = Math.abs(planned(b, m.track, t + 50) - planned(b, m.track, t - 50)) / 100e-6;
        const bound = 1 + v * (Math.abs(modelError_us(b, m.device, t)) + REFIT_US) * 1e-6 * m.stepsPerMm;
        worstExcess = Math.max(worstExcess, error - bound);
        worstSteps = Math.max(worstSteps, error);
        samples++;
      }
      if (b.maxl.estimate().speed > 1) moving++;
    },
    250,
  );
  return { worstExcess, worstSteps, samples, moving };
}
