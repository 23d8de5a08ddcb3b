/**
 * The simulated presets, running in real time inside the worker: each device is
 * a wasm instance of a real firmware example (served from /firmware/), behind a
 * USB-like link model, driving one plant.
 */
import type { Scheduler } from '../../core/index.ts';
import { createSimulatedMachine, type SimulatedMachine } from '../../core/sim/machine.ts';
import { fetchWasmLoader } from '../../core/sim/device/wasmLoader.ts';
import { PRESETS } from '../../core/sim/presets/index.ts';
import type { MachineConfig, PresetView } from './protocol.ts';

export function presetViews(): PresetView[] {
  return Object.values(PRESETS).map((make) => {
    const p = make();
    return { id: p.id, description: p.description };
  });
}

export function presetConfig(id: string): MachineConfig {
  const make = PRESETS[id];
  if (!make) throw new Error(`there is no simulated machine "${id}" (presets: ${Object.keys(PRESETS).join(', ')})`);
  return make().config as MachineConfig;
}

/** µs between device loop() calls while busy, in the browser (the presets' default is 20). */
const BROWSER_LOOP_PERIOD_US = 100;

const loader = fetchWasmLoader(new URL('/firmware/', self.location.href).href);

export async function startSimulatedMachine(id: string, scheduler: Scheduler, onError: (err: unknown) => void): Promise<SimulatedMachine> {
  const make = PRESETS[id];
  if (!make) throw new Error(`there is no simulated machine "${id}"`);
  const preset = make();
  // The page runs for hours: keep only the accelerometer's last 60 000 samples (1 minute at
  // the Accelerometer example's 1 kHz) as ground truth, for the capture tool's stamp check.
  if (preset.plant.accelerometer) preset.plant.accelerometer = { ...preset.plant.accelerometer, recordSamples: 60_000 };
  // Device loops every 100 µs rather than the presets' 20: in real time every loop
  // costs this worker CPU, and a busy worker delays the author's own timers.
  return createSimulatedMachine(preset, scheduler, { loader, onError, seed: 1, loopPeriod_us: BROWSER_LOOP_PERIOD_US });
}

/** Ground truth for the page: each motor's step count. */
export function truthOf(sim: SimulatedMachine): Record<string, number> {
  sim.sync();
  return sim.plant.motorSteps();
}
