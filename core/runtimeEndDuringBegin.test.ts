/**
 * end() while begin() is still connecting (devices saying hello, clocks syncing):
 * begin() rejects at once with QUEUE_CLOSED, whatever step it was at, and nothing
 * it started keeps running. The workbench ends an author this way when the user
 * picks another machine while the first is still connecting; a begin() that waited
 * on (or carried on after) the ended author held the next machine back for good.
 * Runs the simulated light painter (real firmware in wasm) in virtual time.
 */
import { describe, expect, it } from 'vitest';
import { createMAXL, MaxlError, VirtualScheduler, type Link } from './index.ts';
import { createSimulatedMachine } from './sim/machine.ts';
import { nodeWasmLoader } from './sim/device/nodeWasmLoader.ts';
import { lightPainter } from './sim/presets/index.ts';

/** A light painter whose links count the bytes the author writes to them. */
async function countingMachine() {
  const scheduler = new VirtualScheduler(0);
  const sim = await createSimulatedMachine(lightPainter(), scheduler, { seed: 1, loader: nodeWasmLoader() });
  const written = { bytes: 0 };
  const links = Object.values(sim.links).map((link): Link => {
    const writable = new WritableStream<Uint8Array>({
      async write(chunk) {
        written.bytes += chunk.length;
        const w = link.writable.getWriter();
        try {
          await w.write(chunk);
        } finally {
          w.releaseLock();
        }
      },
    });
    return { ...link, writable };
  });
  const maxl = createMAXL(sim.config, { links, scheduler });
  return { scheduler, sim, maxl, written };
}

/** How begin() settled within `limit_us` of virtual time: 'pending', 'resolved', or the error. */
async function outcome(scheduler: VirtualScheduler, begun: Promise<unknown>, limit_us: number): Promise<unknown> {
  let result: unknown = 'pending';
  begun.then(
    () => (result = 'resolved'),
    (err: unknown) => (result = err),
  );
  await scheduler.runWhile(() => result === 'pending', scheduler.now() + limit_us);
  return result;
}

describe('end() while begin() connects', () => {
  it('during the clock sync: begin() rejects with QUEUE_CLOSED at once, and nothing is sent after', async () => {
    const { scheduler, sim, maxl, written } = await countingMachine();
    const begun = maxl.begin();
    // Hellos and subscriptions take a few ms; the sync before streaming lasts 2 s.
    await scheduler.advance(500_000);
    expect(maxl.devices().every((d) => d.state === 'open' || d.state === 'opening')).toBe(true);
    const ended = maxl.end();
    const result = await outcome(scheduler, begun, 10_000);
    await ended;
    expect(result).toBeInstanceOf(MaxlError);
    expect((result as MaxlError).code).toBe('QUEUE_CLOSED');
    const bytesAtEnd = written.bytes;
    // Well past where the sync would have ended and streaming begun.
    await scheduler.advance(5_000_000);
    expect(written.bytes).toBe(bytesAtEnd);
    await sim.stop();
  });

  it('before the devices said hello: begin() rejects with QUEUE_CLOSED at once', async () => {
    const { scheduler, sim, maxl } = await countingMachine();
    const begun = maxl.begin();
    const ended = maxl.end();
    const result = await outcome(scheduler, begun, 10_000);
    await ended;
    expect(result).toBeInstanceOf(MaxlError);
    expect((result as MaxlError).code).toBe('QUEUE_CLOSED');
    await sim.stop();
  });
});
