/**
 * The simulated boards behind the fake navigator.serial, in their own worker (as
 * real boards are their own computers): the workbench's own simulated machine,
 * whose links' author ends are transferred to the page as the fake ports' streams.
 * The boards run on paced virtual time: like firmware, which loops without
 * waiting on a browser's timers, every device loop and link delay happens at its
 * own time; only the author, in the app's worker, is subject to real-time delays.
 */
/// <reference lib="webworker" />
import { PacedScheduler } from '../../core/index.ts';
import type { SimulatedMachine } from '../../core/sim/machine.ts';
import { startSimulatedMachine } from '../../app/worker/simulatedMachines.ts';

const scope = self as unknown as DedicatedWorkerGlobalScope;
let sim: SimulatedMachine | null = null;

scope.onmessage = async (m: MessageEvent<{ type: 'start'; presetId: string } | { type: 'truth'; id: number }>) => {
  const msg = m.data;
  if (msg.type === 'start') {
    sim = await startSimulatedMachine(msg.presetId, new PacedScheduler(), (err) => console.error('fake boards:', err));
    const ports = Object.entries(sim.links).map(([name, link]) => ({ name, readable: link.readable, writable: link.writable }));
    scope.postMessage({ type: 'ready', ports }, ports.flatMap((p) => [p.readable, p.writable]) as unknown as Transferable[]);
  } else if (msg.type === 'truth' && sim) {
    sim.sync();
    scope.postMessage({ type: 'truth', id: msg.id, steps: sim.plant.motorSteps() });
  }
};
