/**
 * The simulated boards behind the fake navigator.serial, in their own worker (as
 * real boards are their own computers): a simulated machine in real time, whose
 * links' author ends are transferred to the page as the fake ports' streams.
 * The boards run on paced virtual time: like firmware, which loops without
 * waiting on a browser's timers, every device loop and link delay happens at its
 * own time; only the author, in the app's worker, is subject to real-time delays.
 */
/// <reference lib="webworker" />
import { PacedScheduler } from '../../core/index.ts';
import { createSimulatedMachine, type SimulatedMachine } from '../../core/sim/machine.ts';
import { fetchWasmLoader } from '../../core/sim/device/wasmLoader.ts';
import { PRESETS } from '../../core/sim/presets/index.ts';

const scope = self as unknown as DedicatedWorkerGlobalScope;
let sim: SimulatedMachine | null = null;

scope.onmessage = async (m: MessageEvent<{ type: 'start'; presetId: string } | { type: 'truth'; id: number }>) => {
  const msg = m.data;
  if (msg.type === 'start') {
    const preset = PRESETS[msg.presetId]();
    sim = await createSimulatedMachine(preset, new PacedScheduler(), { loader: fetchWasmLoader(new URL('/firmware/', self.location.href).href), loopPeriod_us: 100 });
    const ports = preset.devices.map((d) => ({ name: d.name, readable: sim!.links[d.name].readable, writable: sim!.links[d.name].writable }));
    scope.postMessage({ type: 'ready', ports }, ports.flatMap((p) => [p.readable, p.writable]) as unknown as Transferable[]);
  } else if (msg.type === 'truth' && sim) {
    sim.sync();
    scope.postMessage({ type: 'truth', id: msg.id, steps: sim.plant.motorSteps() });
  }
};
