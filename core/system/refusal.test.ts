/**
 * A device refuses a frame mid-job, for what it says: the runtime stops streaming
 * to every device, says why once (an `error` with DEVICE_REFUSED, then
 * `streamStopped`), and the machine runs out of timing and comes to rest on the path.
 *
 * The refusal is real: the simulated Blot's link rewrites the 41st TIMING frame
 * with a negative alpha and a correct CRC (sim/testing/tamperLink.ts), and the
 * firmware in wasm refuses it as MALFORMED.
 */
import { describe, expect, it } from 'vitest';
import { MaxlError } from '../errors.ts';
import type { Message } from '../net/messages.ts';
import { blotPlotter } from '../sim/presets/index.ts';
import { tamperLink } from '../sim/testing/tamperLink.ts';
import { corneredPath } from './geometry.ts';
import { restingPlace, settle, startMachine } from './harness.ts';

/** The shared path, closed back to its start. */
const PATH = [...corneredPath(), [10, 10]];

/** Which TIMING frame the link spoils: one well into the job. */
const REFUSED = 40;

/** The `which`-th TIMING frame (from 0) with its first segment's alpha negative. */
function refuseTiming(which: number) {
  let seen = 0;
  return (_seq: number, m: Message): Message => {
    if (m.type !== 'TIMING' || seen++ !== which) return m;
    return { ...m, segments: m.segments.map((s, k) => (k === 0 ? { ...s, alpha: -1 } : s)) };
  };
}

describe('a device refuses a frame mid-job', () => {
  it('stops the stream for good, says why, and the machine rests on the path', async () => {
    const b = await startMachine(blotPlotter(), { seed: 7, wrapLink: (link) => tamperLink(link, 'TIMING', refuseTiming(REFUSED)) });
    const start = b.maxl.queue.tailPosition as number[];
    const added = PATH.map((p) => b.maxl.addSegmentToQueue({ endPosition: p }));
    let idleOutcome: unknown = 'pending';
    b.maxl.whenIdle().then(
      () => (idleOutcome = 'resolved'),
      (err: unknown) => (idleOutcome = err),
    );
    await b.scheduler.runWhile(() => !b.events.some((e) => e.type === 'streamStopped'), b.scheduler.now() + 20_000_000);
    const stoppedAt = b.scheduler.now();
    expect(b.events.some((e) => e.type === 'streamStopped')).toBe(true);

    // One error, before streamStopped, saying which device refused what and why.
    const errors = b.events.filter((e) => e.type === 'error');
    expect(errors).toHaveLength(1);
    expect(errors[0].text).toMatch(/^blot: TIMING was refused \(MALFORMED, detail 6\)\. Streaming stopped/);
    expect(b.events.findIndex((e) => e.type === 'error')).toBeLessThan(b.events.findIndex((e) => e.type === 'streamStopped'));

    // The machine brakes along the geometry it holds and comes to rest on the path.
    const rest = await restingPlace(b, [start, ...PATH]);
    expect(rest.movedWhileWatched).toBe(false);
    expect(rest.offPath_mm).toBeLessThan(0.03);
    const carriage = rest.carriage;
    // Mid-job: past the first corner, short of the last (the path ends where it began, at (10, 10)).
    expect(Math.hypot(carriage.x - 10, carriage.y - 10)).toBeGreaterThan(5);
    expect(carriage.x + carriage.y).toBeGreaterThan(25);
    // It said where it stopped: the devices' 'stopped' reports name a point of the path.
    const stop = b.events.find((e) => e.type === 'stopped' && e.at > stoppedAt);
    const position = (JSON.parse(stop!.text) as { position: number[] }).position;
    expect(Math.hypot(position[0] - carriage.x, position[1] - carriage.y)).toBeLessThan(0.05);

    // No second error: not the "stream fell behind" of a device braking for want of timing.
    expect(b.events.filter((e) => e.type === 'error')).toHaveLength(1);
    // The job's waits end: whenIdle rejects with the same MaxlError (the job will not run to its
    // end, so it must not wait forever), now and when asked again; the queued moves had been accepted.
    await settle(b.scheduler, Promise.all(added), 1_000_000);
    expect(idleOutcome).toBeInstanceOf(MaxlError);
    expect((idleOutcome as MaxlError).code).toBe('DEVICE_REFUSED');
    await expect(b.maxl.whenIdle()).rejects.toBe(idleOutcome);
    // Cancel and pause still work: they resolve (the machine is already at rest), they do not rethrow.
    await settle(b.scheduler, b.maxl.cancel(), 1_000_000);
    await settle(b.scheduler, b.maxl.pause(), 1_000_000);
    await b.sim.stop();
  }, 120_000);
});
