/**
 * The examples' compile-time options (firmware/README.md), seen from the author
 * through the real firmware in wasm: BlotPlotter is built with MAXL_HALT_BRAKE 0,
 * so HALT mode 1 is refused MALFORMED, while HALT mode 0 (what the runtime sends
 * to stop) still works; LightPainter, built with the library's defaults, accepts
 * both.
 */
import { describe, expect, it } from 'vitest';
import { blotPlotter, lightPainter } from '../sim/presets/index.ts';
import type { SendResult } from '../net/session.ts';
import type { Message } from '../net/messages.ts';
import { settle, startMachine, type Bench } from './harness.ts';

function sendTo(b: Bench, device: string, m: Message): Promise<SendResult> {
  const runtime = (b.maxl as unknown as { runtime: { sessions: Array<{ info: { name: string }; send(m: Message): Promise<SendResult> }> } }).runtime;
  const session = runtime.sessions.find((s) => s.info.name === device);
  if (!session) throw new Error(`no session with ${device}`);
  return session.send(m);
}

describe('compile-time options in the examples', () => {
  it('BlotPlotter refuses HALT mode 1 (left out) and obeys HALT mode 0', async () => {
    const b = await startMachine(blotPlotter());
    expect(await settle(b.scheduler, sendTo(b, 'blot', { type: 'HALT', mode: 1, at: 0 }), 1_000_000)).toEqual({ ok: false, reason: 'MALFORMED', detail: 0x09 });
    expect(await settle(b.scheduler, sendTo(b, 'blot', { type: 'HALT', mode: 0, at: 0 }), 1_000_000)).toEqual({ ok: true });
    await b.sim.stop();
  }, 60_000);

  it('an example built with the defaults (LightPainter) accepts HALT mode 1', async () => {
    const preset = lightPainter();
    const b = await startMachine(preset);
    const device = preset.devices.find((d) => d.example === 'LightPainter')!.name;
    expect(await settle(b.scheduler, sendTo(b, device, { type: 'HALT', mode: 1, at: 0 }), 1_000_000)).toEqual({ ok: true });
    await b.sim.stop();
  }, 60_000);
});
