/**
 * `npm run bench -- simulator [hours] [pingEvery_ms] [preset]`: the simulator
 * (real firmware in wasm) in virtual time. Two figures, one JSON line:
 *   idle: `preset` (default lightPainter) with every device idle and a PING
 *         to each every `pingEvery_ms` (default 100) for `hours` (default 1);
 *   busy: the accelerometer rig moving x at 100 mm/s for 60 s with its
 *         accelerometer subscribed (both boards looping every 20 µs).
 */
import { PROTOCOL_VERSION } from '../core/net/protocol.ts';
import { VirtualScheduler } from '../core/time/virtualScheduler.ts';
import { nodeWasmLoader } from '../core/sim/device/nodeWasmLoader.ts';
import { createSimulatedMachine } from '../core/sim/machine.ts';
import { PRESETS } from '../core/sim/presets/index.ts';
import { FrameClient } from '../core/sim/testing/frameClient.ts';
import { DeviceDriver } from '../core/sim/testing/drive.ts';

const hours = Number(process.argv[2] ?? 1);
const pingEvery_us = Number(process.argv[3] ?? 100) * 1000;
const presetId = process.argv[4] ?? 'lightPainter';
const loader = nodeWasmLoader();

async function idle() {
  const s = new VirtualScheduler();
  const sim = await createSimulatedMachine(PRESETS[presetId](), s, { seed: 1, loader });
  const pingSentAt = new Map<string, number>();
  const rtt = { min: Infinity, max: -Infinity, sum: 0, n: 0 };
  const pongs: Record<string, number> = {};
  const end_us = hours * 3600e6;
  for (const [name, link] of Object.entries(sim.links)) {
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
    s.at(1000, () => client.send(0, { type: 'HELLO_REQUEST', protocol: PROTOCOL_VERSION }));
    let seq = 1;
    const ping = () => {
      pingSentAt.set(`${name}/${seq & 0xffff}`, s.now());
      client.send(seq & 0xff, { type: 'PING', pingId: seq & 0xffff, replyAfter: 0 });
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
  return {
    preset: presetId,
    simulated_h: hours,
    pingEvery_ms: pingEvery_us / 1000,
    wall_s: round(wall_s),
    wallPerSimulatedHour_s: round(wall_s / hours),
    pongs,
    pingRoundTrip_us: { min: Math.round(rtt.min), mean: Math.round(rtt.sum / rtt.n), max: Math.round(rtt.max) },
    deviceLoops: Object.fromEntries(Object.entries(sim.devices).map(([n, d]) => [n, d.counters.loops])),
  };
}

async function busy() {
  const s = new VirtualScheduler();
  const sim = await createSimulatedMachine(PRESETS.accelRig(), s, { seed: 1, loader });
  const motor = new DeviceDriver(s, sim, 'motorOne');
  const imu = new DeviceDriver(s, sim, 'accelerometer');
  s.at(1000, () => {
    motor.hello();
    motor.subscribe(0, 'position', 0);
    motor.cruise(0, [0], [6000], 6000, 100_000, 60_000_000);
    imu.hello();
    imu.subscribe(0, 'sensor', 0);
  });
  const wall0 = performance.now();
  await s.runUntil(61_000_000);
  const wall_s = (performance.now() - wall0) / 1000;
  sim.sync();
  await sim.stop();
  return {
    preset: 'accelRig',
    simulated_s: 61,
    wall_s: round(wall_s),
    realTimeFactor: round(61 / wall_s),
    steps: sim.plant.motorSteps().x,
    deviceLoops: Object.fromEntries(Object.entries(sim.devices).map(([n, d]) => [n, d.counters.loops])),
    sampleBatches: imu.client.of('SAMPLES').length,
  };
}

const round = (x: number) => Number(x.toFixed(2));
console.log(JSON.stringify({ bench: 'simulator', idle: await idle(), busy: await busy() }));
