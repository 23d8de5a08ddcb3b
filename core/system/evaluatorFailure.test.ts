/**
 * An event evaluator that throws, or returns a non-number, while its segment is
 * being locked (issue 11, item 2): the failure never escapes the scheduler's timer
 * (VirtualScheduler would rethrow it here, as a browser worker would die of it). It
 * becomes one `error` event with the evaluator's MaxlError, the stream stops and
 * the machine brakes to rest on the path, whenIdle() rejects with that error, and
 * cancel() resolves without rethrowing it.
 */
import { describe, expect, it } from 'vitest';
import { MaxlError } from '../errors.ts';
import type { EvaluatorState } from '../trajectory/events.ts';
import { lightPainter } from '../sim/presets/index.ts';
import { restingPlace, settle, startMachine } from './harness.ts';

const PATH = [
  [20, 20],
  [90, 20],
  [90, 40],
  [20, 40],
];

const failures: Array<[string, (s: EvaluatorState) => number, RegExp]> = [
  [
    'throws',
    (s) => {
      if (s.position.x > 50) throw new Error('no pattern past x = 50');
      return 1;
    },
    /eventChannels\.neopixelBitmap: evaluator threw at t = [\d.]+ s: no pattern past x = 50/,
  ],
  ['returns a string', (s) => (s.position.x > 50 ? ('bright' as unknown as number) : 1), /eventChannels\.neopixelBitmap: evaluator returned bright at t = [\d.]+ s; it must return a finite number/],
];

describe('an event evaluator fails mid-job', () => {
  it.each(failures)('one that %s: an error event, the machine rests on the path, cancel() does not rethrow', async (_what, evaluator, message) => {
    const b = await startMachine(lightPainter(), { seed: 9 });
    const start = b.maxl.queue.tailPosition as number[];
    const eventChannels = [{ name: 'neopixelBitmap', evaluationPrecision: 10, evaluator }];
    for (const [i, p] of PATH.entries()) void b.maxl.addSegmentToQueue({ endPosition: p, maxVelocity: 60, ...(i === 1 ? { eventChannels } : {}) });
    let idleOutcome: unknown = 'pending';
    b.maxl.whenIdle().then(
      () => (idleOutcome = 'resolved'),
      (err: unknown) => (idleOutcome = err),
    );
    // No exception out of any timer: runWhile would rethrow it.
    const stopped = await b.scheduler.runWhile(() => !b.events.some((e) => e.type === 'streamStopped'), b.scheduler.now() + 20_000_000);
    expect(stopped).toBe(true);
    const errors = b.events.filter((e) => e.type === 'error');
    expect(errors).toHaveLength(1);
    expect(errors[0].text).toMatch(message);
    expect(idleOutcome).toBeInstanceOf(MaxlError);
    expect((idleOutcome as MaxlError).code).toBe('MOVE_INVALID');

    // The devices run out of timing before the failing segment and rest on the path.
    const rest = await restingPlace(b, [start, ...PATH]);
    expect(rest.movedWhileWatched).toBe(false);
    expect(rest.offPath_mm).toBeLessThan(0.03);
    const carriage = rest.carriage;
    // The move is locked a slice at a time: the slices before x = 50 ran, and the machine
    // braked along the geometry it held past that point, far short of the move's end (x = 90).
    expect(carriage.x).toBeGreaterThan(40);
    expect(carriage.x).toBeLessThan(60);
    expect(carriage.y).toBeCloseTo(20, 1);

    // cancel() resolves (nothing to stop), and nothing more went wrong.
    await settle(b.scheduler, b.maxl.cancel(), 1_000_000);
    expect(b.events.filter((e) => e.type === 'error')).toHaveLength(1);
    await b.sim.stop();
  }, 120_000);
});
