/**
 * begin() and the calls that need it, refused with a MaxlError that says what is
 * wrong (docs/bad-input.md): no links, subscriptions that do not match what the
 * devices report, and motion calls before begin().
 */
import { describe, expect, it } from 'vitest';
import { createMAXL } from '../index.ts';
import { MaxlError } from '../errors.ts';
import { accelRig, blotPlotter } from '../sim/presets/index.ts';
import { WIRE_MIN_SEGMENT_S } from '../trajectory/moves.ts';
import { createSimulatedMachine } from '../sim/machine.ts';
import { nodeWasmLoader } from '../sim/device/nodeWasmLoader.ts';
import { VirtualScheduler } from '../time/virtualScheduler.ts';
import { settle, startMachine } from './harness.ts';

async function refusal(promise: Promise<unknown>): Promise<MaxlError> {
  const err = await promise.then(
    () => null,
    (e: unknown) => e,
  );
  expect(err).toBeInstanceOf(MaxlError);
  return err as MaxlError;
}

describe('begin() refuses', () => {
  it('with no links: DEVICE_UNAVAILABLE', async () => {
    const maxl = createMAXL({ motionAxes: ['x'], limits: { maxVelocity: 10, maxAcceleration: 100 } }, { links: [] });
    const err = await refusal(maxl.begin());
    expect(err.code).toBe('DEVICE_UNAVAILABLE');
    expect(err.message).toMatch(/no links to open/);
  });

  it('a link declaring a UART byte time that is not a finite µs ≥ 0: DEVICE_UNAVAILABLE naming the link and the field, before any link is opened', async () => {
    const scheduler = new VirtualScheduler();
    const sim = await createSimulatedMachine(blotPlotter(), scheduler, { seed: 1, loader: nodeWasmLoader() });
    const [good] = Object.values(sim.links);
    for (const bad of [NaN, -40, Infinity]) {
      const link = { readable: new ReadableStream<Uint8Array>(), writable: new WritableStream<Uint8Array>(), label: 'uno', uartByteTime_us: bad };
      const maxl = createMAXL(sim.config, { links: [good, link], scheduler });
      const err = await refusal(maxl.begin());
      expect(err.code).toBe('DEVICE_UNAVAILABLE');
      expect(err.field).toBe('links[1].uartByteTime_us');
      expect(err.message).toMatch(/link 1 \(uno\) declares uartByteTime_us/);
      // Nothing was opened: the good link is still free for another author.
      expect(good.readable.locked).toBe(false);
      expect(good.writable.locked).toBe(false);
    }
  });

  it('a subscription to a reader the device does not have: SUBSCRIPTION_MISMATCH naming it', async () => {
    const scheduler = new VirtualScheduler();
    const sim = await createSimulatedMachine(blotPlotter(), scheduler, { seed: 1, loader: nodeWasmLoader() });
    const config = { ...sim.config, subscriptions: sim.config.subscriptions!.map((s, i) => (i === 0 ? { ...s, reader: 'noSuchReader' } : s)) };
    const maxl = createMAXL(config, { links: Object.values(sim.links), scheduler });
    const err = await settle(scheduler, refusal(maxl.begin()), 5_000_000);
    expect(err.code).toBe('SUBSCRIPTION_MISMATCH');
    expect(err.message).toMatch(/noSuchReader/);
    await sim.stop();
  });
});

describe('before begin()', () => {
  it('pause, cancel, halt and whenIdle throw NOT_STARTED; moves still queue', async () => {
    const maxl = createMAXL({ motionAxes: ['x'], limits: { maxVelocity: 10, maxAcceleration: 100 } });
    for (const call of [() => maxl.pause(), () => maxl.cancel(), () => maxl.halt(), () => maxl.whenIdle()]) {
      expect(call).toThrow(expect.objectContaining({ code: 'NOT_STARTED', message: 'call begin() first' }));
    }
    await expect(maxl.addSegmentToQueue({ endPosition: [1] })).resolves.toMatchObject({ skipped: false });
  });
});

describe('after begin()', () => {
  it('a segment too short to time in whole µs lasts 2 µs, never 0 (which the reader refuses)', async () => {
    const b = await startMachine(accelRig(), { seed: 2 });
    // 2 nm: 0.09 µs at the rig's acceleration without the wire's floor (moves.ts WIRE_MIN_SEGMENT_S).
    await settle(b.scheduler, b.maxl.addSegmentToQueue({ endPosition: [2e-6] }), 1_000_000);
    const seg = b.maxl.queue.segments()[0];
    expect(seg.length).toBeCloseTo(2e-6, 12);
    await b.scheduler.advance(500_000);
    expect(seg.duration_s).toBeGreaterThanOrEqual(WIRE_MIN_SEGMENT_S * (1 - 1e-9));
    expect(b.events.filter((e) => e.type === 'error')).toEqual([]);
    await b.sim.stop();
  }, 60_000);
});
