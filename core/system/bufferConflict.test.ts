/**
 * A path too fine for its speed: 24 µm segments at 200 mm/s need far more segments
 * ahead (braking from 200 mm/s at 2 000 mm/s² takes 10 mm, 400 of them) than a
 * device's queue of 64 holds. The streamer brakes the machine to rest on the path and
 * sends nothing past it (core/net/streamer.ts "Capacity"). The runtime says so as it
 * says every stop off the plan: an `error` (BUFFER_CONFLICT), then `streamStopped`;
 * and a wait for the job's end rejects with the conflict. It once resolved at rest,
 * as if the job were done, and said nothing but the error. Real firmware (the
 * simulated light painter, in wasm), virtual time.
 */
import { describe, expect, it } from 'vitest';
import { MaxlError } from '../errors.ts';
import { lightPainter } from '../sim/presets/index.ts';
import { startMachine } from './harness.ts';

describe('a buffer conflict', () => {
  it('brings the machine to rest, says why, stops the stream, and the wait for the end rejects with it', async () => {
    const b = await startMachine(lightPainter());
    const moves = Array.from({ length: 4000 }, (_, k) => ({ endPosition: [10 + 0.024 * (k + 1), 20], maxVelocity: 200 }));
    await b.maxl.addSegmentToQueue({ endPosition: [10, 20] });
    await b.scheduler.advance(1_000_000);
    const feeding = b.maxl.addSegmentsToQueue(moves).catch(() => undefined);
    let idleOutcome: unknown = 'pending';
    b.maxl.whenIdle().then(
      () => (idleOutcome = 'resolved'),
      (err: unknown) => (idleOutcome = err),
    );
    await b.scheduler.runWhile(() => !b.events.some((e) => e.type === 'streamStopped'), b.scheduler.now() + 20_000_000);
    const errors = b.events.filter((e) => e.type === 'error');
    expect(errors[0].text).toMatch(/^buffer conflict: segment \d+ \(0\.024 mm at up to 200\.0 mm\/s\) needs more segments ahead than a device's queue of 64 holds/);
    const stopped = b.events.find((e) => e.type === 'streamStopped')!;
    expect(JSON.parse(stopped.text)).toMatchObject({ device: null, what: 'a buffer conflict stopped the stream, and the machine brakes to rest on the path' });
    expect(b.events.indexOf(errors[0])).toBeLessThan(b.events.indexOf(stopped));
    // At rest on the path, well short of its end, and it stays there.
    await b.scheduler.advance(2_000_000);
    const rest = b.maxl.estimate();
    expect(rest.speed).toBe(0);
    expect(rest.position[0]).toBeLessThan(10 + 0.024 * 4000 - 10);
    expect(idleOutcome).toBeInstanceOf(MaxlError);
    expect((idleOutcome as MaxlError).code).toBe('BUFFER_CONFLICT');
    await expect(b.maxl.whenIdle()).rejects.toMatchObject({ code: 'BUFFER_CONFLICT' });
    await b.scheduler.advance(1_000_000);
    expect(b.maxl.estimate().position).toEqual(rest.position);
    void feeding;
    await b.maxl.end();
    await b.sim.stop();
  });
});
