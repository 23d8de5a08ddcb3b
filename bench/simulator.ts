/**
 * `npm run bench -- simulator [hours] [pingEvery_ms] [preset]`: an idle
 * simulated machine (real firmware in wasm, devices idle) in virtual time,
 * with a PING to every device every `pingEvery_ms` (default 100) for `hours`
 * (default 1). Prints the wall time it took and what ran, as JSON.
 */
import { PROTOCOL_VERSION } from '../core/net/protocol.ts';
import { VirtualScheduler } from '../core/time/virtualScheduler.ts';
import { nodeWasmLoader } from '../core/sim/device/nodeWasmLoader.ts';
import { createSimulatedMachine } from '../core/sim/machine.ts';
import { PRESETS } from '../core/sim/presets/index.ts';
import { FrameClient } from '../core/sim/testing/frameClient.ts';

const hours = Number(process.argv[2] ?? 1);
const pingEvery_us = Number(process.argv[3] ?? 100) * 1000;
const presetId = process.argv[4] ?? 'lightPainter';

const s = new VirtualScheduler();
const sim = await createSimulatedMachine(PRESETS[presetId](), s, { seed: 1, loader: nodeWasmLoader() });
const pingSentAt = new Map<string, number>();
const rtt = { min: Infinity, max: -Infinity, sum: 0, n: 0 };
const pongs: Record<string, number> = {};
const clients = Object.entries(sim.links).map(([name, link]) => {
  pongs[name] = 0;
  const client = new FrameClient(s, link, {
    keep: false,
    onMessage: (r) => {
      if (r.message.type !== 'PONG') return;
      pongs[name]++;
      const d = r.t_us - (pingSentAt.get(`${name}/${r.message.pingId}`) ?? NaN);
      rtt.min = Math.min(rtt.min, d);
      rtt.max = Math.max(rtt.max, d);
      rtt.sum += d;
      rtt.n++;
    },
  });
  return [name, client] as const;
});
const end_us = hours * 3600e6;
for (const [name, c] of clients) {
  s.at(1000, () => c.send(0, { type: 'HELLO_REQUEST', protocol: PROTOCOL_VERSION }));
  let seq = 1;
  const ping = () => {
    pingSentAt.set(`${name}/${seq & 0xffff}`, s.now());
    c.send(seq & 0xff, { type: 'PING', pingId: seq & 0xffff });
    seq++;
    if (s.now() + pingEvery_us < end_us) s.after(pingEvery_us, ping);
  };
  s.at(10_337, ping); // off the USB frame grid
}
const wall0 = performance.now();
await s.runUntil(end_us);
const wall_s = (performance.now() - wall0) / 1000;
sim.sync();
await sim.stop();
console.log(
  JSON.stringify({
    bench: 'simulator',
    preset: presetId,
    simulated_h: hours,
    pingEvery_ms: pingEvery_us / 1000,
    wall_s: Number(wall_s.toFixed(2)),
    wallPerSimulatedHour_s: Number((wall_s / hours).toFixed(2)),
    pongs,
    pingRoundTrip_us: { min: Math.round(rtt.min), mean: Math.round(rtt.sum / rtt.n), max: Math.round(rtt.max) },
    deviceLoops: Object.fromEntries(Object.entries(sim.devices).map(([n, d]) => [n, d.counters.loops])),
  }),
);
