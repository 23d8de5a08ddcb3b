/**
 * The dry run before real boards stream (warmUp.ts): it runs the streaming path
 * (planning, slicing, geometry, timing, frames) and reaches no board, and the
 * author's own queue and timeline are as they would have been without it.
 */
import { describe, expect, it } from 'vitest';
import { startMachine } from '../system/harness.ts';
import { lightPainter } from '../sim/presets/index.ts';
import { resolveConfig } from '../config/validate.ts';
import { warmStreamingPaths } from './warmUp.ts';
import type { Link } from './link.ts';
import { unpackFrame } from './frame.ts';
import { MessageType } from './protocol.ts';

const TYPE_NAMES = new Map<number, string>(Object.entries(MessageType).map(([name, code]) => [code, name]));

/** Notes the type of every frame the author writes to a link (frames end in 0x00). */
function watching(link: Link, types: Set<string>): Link {
  const writer = link.writable.getWriter();
  let pending: number[] = [];
  const writable = new WritableStream<Uint8Array>({
    write: (chunk) => {
      for (const byte of chunk) {
        if (byte !== 0) pending.push(byte);
        else if (pending.length > 0) {
          types.add(TYPE_NAMES.get(unpackFrame(Uint8Array.from(pending)).typeCode) ?? 'unknown');
          pending = [];
        }
      }
      return writer.write(chunk);
    },
  });
  return { ...link, writable };
}

describe('the dry run of the streaming path (warmUp)', () => {
  it('encodes the frames of a move on every axis, for every device, and needs no device at all', async () => {
    const preset = lightPainter();
    const config = resolveConfig(preset.config);
    const slots = config.motionAxes.map((_, index) => ({ space: 'motion' as const, index }));
    const bytes = await warmStreamingPaths(config, [
      { name: 'a', positionSlots: slots, eventSlots: new Map(), capacity: 32 },
      { name: 'b', positionSlots: slots, eventSlots: new Map(), capacity: 32 },
    ]);
    // Two devices, each a GEOMETRY and TIMING or more for the move out and the move back.
    expect(bytes).toBeGreaterThan(2 * 2 * 2 * 14);
    expect(await warmStreamingPaths(config, [])).toBe(0);
  });

  it('sends the boards no segment and leaves the queue and the first move as they were', async () => {
    const runs = [];
    for (const warmUp of [false, true]) {
      const types = new Set<string>();
      const { scheduler, sim, maxl } = await startMachine(lightPainter(), { maxl: { warmUp }, wrapLink: (l) => watching(l, types) });
      const atReady = { types: [...types].sort(), steps: sim.plant.motorSteps(), queued: maxl.queue.untransmittedCount, end: maxl.queue.transmittedEnd_us };
      await maxl.addSegmentToQueue({ endPosition: [10, 0], maxVelocity: 50 });
      await scheduler.advance(1_000_000);
      runs.push({ atReady, position: maxl.estimate().position, steps: sim.plant.motorSteps() });
      await maxl.end();
      await sim.stop();
    }
    const [cold, warm] = runs;
    // At ready, with or without the dry run, the boards got the same kinds of frame
    // (hellos, subscriptions, pings) and no segment, and nothing moved or was queued.
    expect(warm.atReady).toEqual(cold.atReady);
    expect(warm.atReady.types).not.toContain('GEOMETRY');
    expect(warm.atReady.types).not.toContain('TIMING');
    expect(warm.position[0]).toBeCloseTo(10, 9);
    expect(warm.position[1]).toBeCloseTo(0, 9);
    expect(warm.steps).toEqual(cold.steps);
  });
});
