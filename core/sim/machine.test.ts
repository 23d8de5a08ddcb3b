/**
 * Each preset boots its real firmware examples in wasm and answers a
 * HELLO_REQUEST over the simulated link with HELLO and the READERs the preset
 * subscribes; the same seed gives the same bytes at the same times.
 *
 * Needs public/firmware/<Example>.wasm (the firmware's wasm build);
 * MAXL_FIRMWARE_DIR points elsewhere.
 */
import { existsSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { PROTOCOL_VERSION, ReaderKind } from '../net/protocol.ts';
import { VirtualScheduler } from '../time/virtualScheduler.ts';
import { nodeWasmLoader, PUBLIC_FIRMWARE_DIR } from './device/nodeWasmLoader.ts';
import { createSimulatedMachine } from './machine.ts';
import { PRESETS } from './presets/index.ts';
import { FrameClient } from './testing/frameClient.ts';

const firmwareDir = process.env.MAXL_FIRMWARE_DIR ?? PUBLIC_FIRMWARE_DIR;
const loader = nodeWasmLoader(firmwareDir);
/** The examples a preset needs that are not built (the whole preset's tests skip, and say so in their name). */
const missing = (presetId: string) =>
  PRESETS[presetId]()
    .devices.map((d) => d.example)
    .filter((example) => !existsSync(`${firmwareDir}/${example}.wasm`));

async function boot(presetId: string, seed: number) {
  const s = new VirtualScheduler();
  const sim = await createSimulatedMachine(PRESETS[presetId](), s, { seed, loader });
  const clients = Object.fromEntries(Object.entries(sim.links).map(([name, link]) => [name, new FrameClient(s, link)]));
  return { s, sim, clients };
}

describe.each(Object.keys(PRESETS))('simulated %s', (presetId) => {
  if (missing(presetId).length > 0) {
    it.skip(`needs ${missing(presetId).map((e) => `${e}.wasm`).join(', ')} in ${firmwareDir} (the firmware's wasm build)`, () => {});
    return;
  }

  it('boots every device, which answers HELLO_REQUEST with HELLO and its READERs, named as the preset subscribes them', async () => {
    const { s, sim, clients } = await boot(presetId, 1);
    for (const client of Object.values(clients)) s.at(5000, () => client.send(0, { type: 'HELLO_REQUEST', protocol: PROTOCOL_VERSION }));
    await s.runUntil(50_000);
    for (const spec of sim.preset.devices) {
      const c = clients[spec.name];
      expect(c.errors).toEqual([]);
      const [hello, ...more] = c.of('HELLO');
      expect(more).toEqual([]);
      expect(hello.message.name).toBe(spec.name);
      expect(hello.message.protocol).toBe(PROTOCOL_VERSION);
      expect(hello.message.readerCount).toBe(spec.readers.length);
      // The answer came back over USB: at least a frame and the two base delays after the request.
      expect(hello.t_us).toBeGreaterThan(5000 + 1000);
      const readers = c.of('READER').map((r) => r.message);
      expect(readers.map((r) => [r.index, r.name, r.kind])).toEqual(spec.readers.map((r, i) => [i, r.name, ReaderKind[r.kind]]));
      expect(c.of('ACK').map((a) => a.message.ackSeq)).toEqual([0]);
    }
    // Every subscription names a device and reader that answered.
    for (const sub of sim.config.subscriptions ?? []) {
      expect(clients[sub.device].of('READER').map((r) => r.message.name)).toContain(sub.reader);
    }
    await sim.stop();
  });

  it('gives the same bytes at the same times for the same seed', async () => {
    const run = async (seed: number) => {
      const { s, sim, clients } = await boot(presetId, seed);
      for (const client of Object.values(clients)) {
        s.at(3000, () => client.send(0, { type: 'HELLO_REQUEST', protocol: PROTOCOL_VERSION }));
        for (let k = 1; k <= 20; k++) s.at(3000 + k * 7000, () => client.send(k, { type: 'PING', pingId: k, replyAfter: 0 }));
      }
      await s.runUntil(200_000);
      await sim.stop();
      return JSON.stringify(Object.entries(clients).map(([n, c]) => [n, c.bytes, c.arrivals]));
    };
    const a = await run(5);
    expect(await run(5)).toBe(a);
    expect(await run(6)).not.toBe(a); // jitter differs
  });
});
