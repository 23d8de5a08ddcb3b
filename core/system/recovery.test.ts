/**
 * Recovery (docs/architecture.md, "Recovery"): after a link cut, a device restart
 * or a HALT, the same author reconnects, re-syncs and runs the rest of the job
 * from where the readers stopped, to the job's end; a new author can take the
 * links over; every step out of order is refused with RECOVERY_ORDER.
 */
import { describe, expect, it } from 'vitest';
import { blotPlotter } from '../sim/presets/index.ts';
import { MaxlError, createMAXL } from '../index.ts';
import { corneredPath, distanceToPolyline } from './geometry.ts';
import { settle, startMachine, type Bench } from './harness.ts';

const PATH = corneredPath();

/** The carriage, from the plant's motors (after sync). */
function carriage(b: Bench): number[] {
  b.sim.sync();
  const c = b.sim.plant.carriage();
  return [c.x, c.y];
}

async function expectCode(p: Promise<unknown> | (() => unknown), code: string): Promise<void> {
  try {
    await (typeof p === 'function' ? p() : p);
  } catch (err) {
    expect(err).toBeInstanceOf(MaxlError);
    expect((err as MaxlError).code).toBe(code);
    return;
  }
  throw new Error(`expected ${code}`);
}

describe('recovery after a link cut', () => {
  it('the same author reconnects and finishes the job at its end, on the path', async () => {
    const b = await startMachine(blotPlotter(), { seed: 3 });
    const start = [...b.maxl.queue.tailPosition];
    for (const p of PATH) void b.maxl.addSegmentToQueue({ endPosition: p });
    const idle = b.maxl.whenIdle();
    let idleError: unknown = null;
    idle.catch((e) => (idleError = e));
    await b.scheduler.advance(1_500_000);
    b.sim.cut('blot');
    await b.scheduler.advance(800_000);
    expect(b.maxl.stopped?.reason).toBe('lost');
    expect((idleError as MaxlError)?.code).toBe('RECOVERY_ORDER'); // whenIdle() does not hang
    const stoppedAt = carriage(b);
    expect(distanceToPolyline(stoppedAt, [start, ...PATH])).toBeLessThan(0.03);
    // Out of order: resume before reconnecting.
    await expectCode(() => b.maxl.resumeJob(), 'RECOVERY_ORDER');
    await expectCode(b.maxl.whenIdle(), 'RECOVERY_ORDER');
    // Still cut: reconnect fails, and can be tried again.
    await expectCode(settle(b.scheduler, b.maxl.reconnect(), 5_000_000), 'DEVICE_UNAVAILABLE');
    b.sim.restore('blot');
    const report = await settle(b.scheduler, b.maxl.reconnect(), 10_000_000);
    expect(report.boards).toHaveLength(1);
    expect(report.boards[0].source).toBe('status');
    expect(Math.hypot(report.resumeFrom![0] - stoppedAt[0], report.resumeFrom![1] - stoppedAt[1])).toBeLessThan(0.03);
    await expectCode(settle(b.scheduler, b.maxl.reconnect(), 1_000_000), 'RECOVERY_ORDER');
    // Nothing moved while reconnecting.
    expect(carriage(b)).toEqual(stoppedAt);
    b.maxl.resumeJob();
    await settle(b.scheduler, b.maxl.whenIdle(), 30_000_000);
    await b.scheduler.advance(200_000);
    const end = carriage(b);
    expect(Math.hypot(end[0] - 80, end[1] - 40)).toBeLessThan(0.02);
    expect(b.maxl.stopped).toBeNull();
    await b.maxl.end();
    await b.sim.stop();
  }, 60_000);

  it('after a cut, a new author takes the same links over cleanly', async () => {
    const b = await startMachine(blotPlotter(), { seed: 4 });
    for (const p of PATH) void b.maxl.addSegmentToQueue({ endPosition: p });
    await b.scheduler.advance(1_000_000);
    b.sim.cut('blot');
    await b.scheduler.advance(800_000);
    expect(b.maxl.stopped?.reason).toBe('lost');
    b.sim.restore('blot');
    const here = carriage(b);
    const second = createMAXL(b.sim.config, { links: Object.values(b.sim.links), scheduler: b.scheduler, initialPosition: here });
    await settle(b.scheduler, second.begin(), 5_000_000);
    void second.addSegmentToQueue({ endPosition: [20, 20] });
    await settle(b.scheduler, second.whenIdle(), 10_000_000);
    await b.scheduler.advance(100_000);
    const end = carriage(b);
    expect(Math.hypot(end[0] - 20, end[1] - 20)).toBeLessThan(0.02);
    await second.end();
    await b.sim.stop();
  }, 60_000);
});

describe('recovery after HALT, and the order of the steps', () => {
  it('reconnect() before any stop, and resumeJob() or discardJob() before reconnect(), are refused', async () => {
    const b = await startMachine(blotPlotter(), { seed: 5 });
    await expectCode(settle(b.scheduler, b.maxl.reconnect(), 1_000_000), 'RECOVERY_ORDER');
    await expectCode(() => b.maxl.resumeJob(), 'RECOVERY_ORDER');
    await expectCode(() => b.maxl.discardJob(), 'RECOVERY_ORDER');
    expect(b.maxl.stopped).toBeNull();
    await b.maxl.end();
    await b.sim.stop();
  }, 60_000);

  it('HALT keeps the rest of the job: reconnect() and resumeJob() finish it', async () => {
    const b = await startMachine(blotPlotter(), { seed: 6 });
    for (const p of PATH) void b.maxl.addSegmentToQueue({ endPosition: p });
    await b.scheduler.advance(1_200_000);
    await settle(b.scheduler, b.maxl.halt(), 1_000_000);
    await b.scheduler.advance(300_000);
    expect(b.maxl.stopped?.reason).toBe('halted');
    const here = carriage(b);
    // The machine already holds at rest: pause() resolves and changes nothing; resume() needs reconnect() first.
    await settle(b.scheduler, b.maxl.pause(), 1_000_000);
    await expectCode(() => b.maxl.resume(), 'RECOVERY_ORDER');
    const report = await settle(b.scheduler, b.maxl.reconnect(), 10_000_000);
    expect(report.stop.reason).toBe('halted');
    expect(Math.hypot(report.resumeFrom![0] - here[0], report.resumeFrom![1] - here[1])).toBeLessThan(0.03);
    expect(report.remaining).toBeGreaterThan(0);
    b.maxl.resumeJob();
    await settle(b.scheduler, b.maxl.whenIdle(), 30_000_000);
    await b.scheduler.advance(200_000);
    const end = carriage(b);
    expect(Math.hypot(end[0] - 80, end[1] - 40)).toBeLessThan(0.02);
    await b.maxl.end();
    await b.sim.stop();
  }, 60_000);

  it('discardJob() drops the rest: the machine stays where it stopped, ready for new moves', async () => {
    const b = await startMachine(blotPlotter(), { seed: 7 });
    for (const p of PATH) void b.maxl.addSegmentToQueue({ endPosition: p });
    await b.scheduler.advance(1_200_000);
    await settle(b.scheduler, b.maxl.halt(), 1_000_000);
    await b.scheduler.advance(300_000);
    const here = carriage(b);
    await settle(b.scheduler, b.maxl.reconnect(), 10_000_000);
    b.maxl.discardJob();
    expect(b.maxl.queue.untransmittedCount).toBe(0);
    await b.scheduler.advance(300_000);
    expect(carriage(b)).toEqual(here);
    void b.maxl.addSegmentToQueue({ endPosition: [20, 20] });
    await settle(b.scheduler, b.maxl.whenIdle(), 10_000_000);
    await b.scheduler.advance(100_000);
    const end = carriage(b);
    expect(Math.hypot(end[0] - 20, end[1] - 20)).toBeLessThan(0.02);
    await b.maxl.end();
    await b.sim.stop();
  }, 60_000);
});
