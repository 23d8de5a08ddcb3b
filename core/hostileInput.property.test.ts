/**
 * Hostile input to the core's API (issue 11 §3): generated configs, moves, dwells,
 * transforms and event evaluators, valid and not, mixed.
 *
 * For every call:
 *  - it succeeds, or fails with a MaxlError (createMAXL throws one; addSegmentToQueue
 *    returns a promise that rejects with one, never throws): no untyped exception;
 *  - a refused move leaves the queue exactly as it was (a snapshot of every segment);
 * and once the accepted moves are planned and locked:
 *  - locking a segment whose evaluator fails throws that MaxlError and locks nothing;
 *  - every frame the streamer would send for them (GEOMETRY, TIMING, EVENTS), encoded
 *    and decoded back, carries only finite numbers, and TIMING only whole, non-negative µs.
 * (The worker's side of a failing evaluator, a timer that must not throw, is
 * core/system/evaluatorFailure.test.ts.)
 */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { createMAXL, queueOf, type Maxl } from './maxl.ts';
import { MaxlError } from './errors.ts';
import type { MaxlConfig, TransformConfig } from './config/types.ts';
import { WIRE_MIN_SEGMENT_S, type Move } from './trajectory/moves.ts';
import type { Segment } from './trajectory/segment.ts';
import { decodeFrame, encodeFrame } from './net/frame.ts';
import type { Message } from './net/messages.ts';
import { ClockMap } from './net/clockMap.ts';
import { geometryMessages, timingMessages, type PositionSlot } from './net/segmentEncoding.ts';

/** Numbers that break naive code, and the occasional ordinary one. */
const hostileNumber = fc.oneof(
  fc.constantFrom(Number.NaN, Infinity, -Infinity, -0, 0, 1e-300, -1e-300, 5e-324, 1e300, -1e300, Number.MAX_VALUE, 2 ** 31, 2 ** 53, 32_768, -32_768, 4e38),
  fc.double(),
  fc.integer({ min: -1000, max: 1000 }),
);
/** Anything at all where a number belongs. */
const hostileValue: fc.Arbitrary<unknown> = fc.oneof(
  { weight: 4, arbitrary: hostileNumber },
  { weight: 1, arbitrary: fc.constantFrom(null, undefined, '10', '', 'NaN', {}, [], [1], true, () => 1, Symbol('x') as unknown) },
);
/** A coordinate in ±60 mm (not fc.double, which mostly gives 0 and the bounds: zero-length moves). */
const saneCoordinate = fc.integer({ min: -6000, max: 6000 }).map((v) => v / 100);

/** Evaluators good and bad; each is a fresh function (some fail only later in a segment). */
const evaluator: fc.Arbitrary<unknown> = fc.oneof(
  fc.constantFrom(
    () => 1,
    (s: { distance: number }) => s.distance,
    () => Number.NaN,
    () => Infinity,
    () => 1e300, // finite as a double, infinite as the wire's f32
    () => 'bright',
    () => undefined,
    () => ({}),
    (s: { time: number }) => (s.time > 0.01 ? Number.NaN : 0),
    () => {
      throw new Error('evaluator bug');
    },
    () => {
      throw 'a string, not an Error';
    },
    (s: { position: Record<string, number> }) => s.position.nope.valueOf(),
  ),
  hostileValue,
);

const eventChannels: fc.Arbitrary<unknown> = fc.oneof(
  fc.dictionary(fc.constantFrom('pen', 'laser', 'nope', '__proto__', ''), hostileValue, { maxKeys: 2 }),
  fc.array(
    fc.oneof(
      fc.record({ name: fc.constantFrom('pen', 'laser', 'nope'), evaluationPrecision: fc.oneof(fc.constantFrom(1, 5, 20), hostileValue), evaluator }),
      fc.record({ name: fc.oneof(fc.constantFrom('pen', 'laser'), hostileValue), value: hostileValue }),
      hostileValue,
    ),
    { maxLength: 2 },
  ),
  hostileValue,
);

/** A move: sane, or hostile in one or more of its parts. */
const move: fc.Arbitrary<unknown> = fc.oneof(
  { weight: 8, arbitrary: fc.record({ endPosition: fc.tuple(saneCoordinate, saneCoordinate) }) },
  { weight: 2, arbitrary: fc.record({ endPosition: fc.array(fc.oneof(saneCoordinate, hostileValue), { maxLength: 3 }) }) },
  { weight: 1, arbitrary: fc.record({ endPosition: fc.dictionary(fc.constantFrom('x', 'y', 'z', 'a', 'constructor'), fc.oneof(saneCoordinate, hostileValue), { maxKeys: 3 }) }) },
  {
    weight: 2,
    arbitrary: fc.record(
      { endPosition: fc.tuple(saneCoordinate, saneCoordinate), maxVelocity: hostileValue, maxAcceleration: hostileValue, eventChannels },
      { requiredKeys: ['endPosition'] },
    ),
  },
  { weight: 2, arbitrary: fc.record({ dwell_s: fc.oneof(fc.double({ min: 0, max: 0.05, noNaN: true }), hostileValue), eventChannels }, { requiredKeys: ['dwell_s'] }) },
  { weight: 1, arbitrary: fc.record({ endPosition: fc.constant([10, 10]), dwell_s: fc.constant(1) }) },
  { weight: 1, arbitrary: hostileValue },
);

/** Transforms of every kind, with hostile matrices and functions among them. */
const fnTransform = (fn: (p: readonly number[]) => unknown, linear: boolean, tolerance?: unknown): TransformConfig =>
  ({ type: 'function', from: ['x', 'y'], to: ['a'], fn, linear, tolerance }) as TransformConfig;
const transforms: fc.Arbitrary<unknown> = fc.oneof(
  fc.constant(undefined),
  fc.constant([{ type: 'corexy', from: ['x', 'y'], to: ['a', 'b'] }]),
  fc.array(fc.array(hostileValue, { minLength: 2, maxLength: 2 }), { minLength: 1, maxLength: 2 }).map((matrix) => [{ type: 'linear', from: ['x', 'y'], to: matrix.map((_, i) => `m${i}`), matrix }]),
  fc.tuple(
    fc.constantFrom<Array<(p: readonly number[]) => unknown>>(
      (p) => [p[0] + p[1]],
      (p) => [Math.hypot(p[0], p[1])],
      (p) => [p[0] > 20 ? Number.NaN : p[0]],
      (p) => [p[0] * 1e6], // beyond the wire's ±32 767 mm
      (p) => {
        if (p[1] > 30) throw new Error('transform bug');
        return [p[1]];
      },
      () => 7,
      () => [],
      () => ['1'],
      () => null,
    ),
    fc.boolean(),
    fc.oneof(fc.constant(undefined), hostileValue),
  ).map(([fn, linear, tolerance]) => [fnTransform(fn, linear, tolerance)]),
  hostileValue,
);

/** Mostly a machine that works (so moves get tried), often one hostile field, sometimes all. */
const saneLimits = fc.record({ maxVelocity: fc.constantFrom(1, 100, 1000), maxAcceleration: fc.constantFrom(10, 1000, 1e5), junctionDeviation: fc.constantFrom(0.001, 0.05) });
const hostileLimits = fc.oneof(
  fc.record({ maxVelocity: fc.oneof(fc.constant(100), hostileValue), maxAcceleration: fc.oneof(fc.constant(1000), hostileValue), junctionDeviation: fc.oneof(fc.constant(0.05), hostileValue) }, { requiredKeys: [] }),
  fc.record({ maxVelocity: fc.array(hostileValue, { maxLength: 3 }), maxAcceleration: fc.array(hostileValue, { maxLength: 3 }) }),
  hostileValue,
);
const saneTransforms = fc.constantFrom(undefined, [{ type: 'corexy', from: ['x', 'y'], to: ['a', 'b'] }], [{ type: 'linear', from: ['x', 'y'], to: ['m'], matrix: [[0.5, 2]] }]);
const saneSoftLimits = fc.constantFrom(undefined, { x: [-50, 50], y: [-50, 50] });
const config: fc.Arbitrary<unknown> = fc.oneof(
  {
    weight: 6,
    arbitrary: fc.record({
      motionAxes: fc.constant(['x', 'y']),
      eventChannels: fc.constant(['pen', 'laser']),
      limits: fc.oneof({ weight: 4, arbitrary: saneLimits }, { weight: 1, arbitrary: hostileLimits }),
      transforms: fc.oneof({ weight: 2, arbitrary: saneTransforms }, { weight: 2, arbitrary: transforms }),
      softLimits: saneSoftLimits,
    }),
  },
  {
    weight: 1,
    arbitrary: fc.record(
      {
        motionAxes: fc.oneof(fc.constant(['x', 'y']), fc.constantFrom([], ['x', 'x'], ['x', ''], 'xy', null)),
        eventChannels: fc.oneof(fc.constant(['pen', 'laser']), fc.constantFrom(['pen', 'pen'], ['x'], [3], 'pen')),
        limits: hostileLimits,
        transforms,
        softLimits: fc.oneof(saneSoftLimits, fc.dictionary(fc.constantFrom('x', 'y', 'q'), fc.oneof(fc.tuple(hostileValue, hostileValue), hostileValue), { maxKeys: 2 })),
        queueCapacity: fc.oneof(fc.constant(undefined), hostileValue),
      },
      { requiredKeys: ['motionAxes', 'limits'] },
    ),
  },
);

function expectMaxlError(err: unknown, what: string): void {
  if (!(err instanceof MaxlError)) throw new Error(`${what} failed with ${err instanceof Error ? `${err.name}: ${err.message}` : `a thrown ${typeof err} ${String(err)}`}, not a MaxlError`);
}

/** Everything a refused call must leave as it was. */
function snapshot(maxl: Maxl): string {
  const q = queueOf(maxl);
  return JSON.stringify({
    segments: q.segments().map((s) => [s.id, s.moveId, s.state, s.start, s.end, s.length, s.dwell_s, s.entry2, s.exit2, s.timing]),
    untransmitted: q.untransmittedCount,
    tail: q.tailPosition,
    next: maxl.nextMoveStart,
  });
}

/** Every number in a decoded message, wherever it sits. */
function numbersIn(value: unknown, out: number[] = []): number[] {
  if (typeof value === 'number') out.push(value);
  else if (Array.isArray(value)) for (const v of value) numbersIn(v, out);
  else if (value && typeof value === 'object') for (const v of Object.values(value)) numbersIn(v, out);
  return out;
}

/** Encodes a message as a frame and decodes it back, as a device would read it. */
function overTheWire(message: Message, positionSlots: number): Message {
  return decodeFrame(encodeFrame(0, message), { positionSlots, channels: 3 }).message;
}

/** How far the cases got: so the property cannot pass by refusing everything. */
const reached = { machines: 0, refusedMoves: 0, acceptedMoves: 0, framesChecked: 0 };

/** Locks every accepted segment and checks what the streamer would send for them. */
function checkTheWire(maxl: Maxl): void {
  const q = queueOf(maxl);
  q.planToRest();
  const segments: Segment[] = [];
  for (;;) {
    const before = snapshot(maxl);
    let seg: Segment | undefined;
    try {
      seg = q.transmitNext(0);
    } catch (err) {
      // A failing evaluator: its MaxlError, and the segment stays queued, unlocked.
      expectMaxlError(err, 'transmitNext');
      expect(snapshot(maxl)).toBe(before);
      break;
    }
    if (!seg) break;
    segments.push(seg);
  }
  if (segments.length === 0) return;
  const c = maxl.config;
  const slots: PositionSlot[] = [...c.motionAxes.map((_, index) => ({ space: 'motion' as const, index })), ...c.actuatorAxes.map((_, index) => ({ space: 'actuator' as const, index }))];
  // As the streamer brakes: at the gentlest acceleration of the moves it holds (1 mm/s² with none).
  const accels = segments.filter((s) => !s.isDwell).map((s) => s.accel);
  const stopDecel = accels.length > 0 ? Math.min(...accels) : 1;
  const messages: Message[] = [
    ...geometryMessages(segments, slots, 0, true),
    ...timingMessages(segments, new ClockMap(0, 12_345, 1.0001), 0, true, stopDecel),
  ];
  for (const seg of segments) {
    for (const track of q.eventTracksOf(seg)) {
      const entries = track.times.map((t, k) => ({ offset: Math.round(t * 1e6), value: track.values[k] }));
      for (let i = 0; i < entries.length; i += 20) {
        const chunk = entries.slice(i, i + 20);
        messages.push({ type: 'EVENTS', segmentId: seg.id & 0xffff, slot: track.channel, firstIndex: i, count: chunk.length, entries: chunk });
      }
    }
  }
  for (const m of messages) {
    reached.framesChecked++;
    const read = overTheWire(m, slots.length);
    const bad = numbersIn(read).filter((n) => !Number.isFinite(n));
    if (bad.length > 0) throw new Error(`${m.type} carries ${bad.join(', ')} on the wire: ${JSON.stringify(m).slice(0, 300)}`);
    if (read.type !== 'TIMING') continue;
    // What the reader requires of a TIMING besides finite numbers (firmware profile.cpp
    // solveProfile): whole µs, a total under 2³¹ µs, and time to cover a length > 0.
    read.segments.forEach((s, k) => {
      const total = s.durations.reduce((a, b) => a + b, 0);
      const seg = segments[read.firstId + k];
      if (!s.durations.every((d) => Number.isInteger(d) && d >= 0) || total >= 2 ** 31 || (total === 0 && seg.length > 0)) {
        throw new Error(`segment ${read.firstId + k} (${seg.length} mm, accel ${seg.accel}) is timed ${JSON.stringify(s.durations)} µs, which the reader refuses`);
      }
    });
  }
}

describe('hostile input to the core', () => {
  it('configs, moves, dwells, transforms and evaluators: a MaxlError or success, the queue unchanged on refusal, nothing non-finite on the wire', async () => {
    await fc.assert(
      fc.asyncProperty(config, fc.array(move, { minLength: 1, maxLength: 8 }), async (cfg, moves) => {
        let maxl: Maxl;
        try {
          maxl = createMAXL(cfg as MaxlConfig);
        } catch (err) {
          expectMaxlError(err, 'createMAXL');
          return;
        }
        reached.machines++;
        // The floor begin() sets with devices (core/runtime.ts); the wire's own floor, on a link that does not say its speed.
        queueOf(maxl).setMinSegmentDuration(WIRE_MIN_SEGMENT_S);
        for (const m of moves) {
          const before = snapshot(maxl);
          let result: Promise<unknown>;
          try {
            result = maxl.addSegmentToQueue(m as Move);
          } catch (err) {
            throw new Error(`addSegmentToQueue threw synchronously (it must reject): ${String(err)}`);
          }
          const outcome = await result.then(
            () => null,
            (err: unknown) => err ?? new Error('rejected with nothing'),
          );
          if (outcome === null) reached.acceptedMoves++;
          else reached.refusedMoves++;
          if (outcome !== null) {
            expectMaxlError(outcome, `addSegmentToQueue(${String(JSON.stringify(m)).slice(0, 200)})`);
            expect(snapshot(maxl)).toBe(before);
          }
        }
        checkTheWire(maxl);
      }),
    );
    console.log(`hostile input: ${JSON.stringify(reached)}`);
    // The generators reach every stage: machines built, moves both refused and accepted, frames on the wire.
    expect(reached.machines).toBeGreaterThan(0);
    expect(reached.refusedMoves).toBeGreaterThan(reached.machines / 2);
    expect(reached.acceptedMoves).toBeGreaterThan(reached.machines);
    expect(reached.framesChecked).toBeGreaterThan(reached.machines);
  }, 600_000); // at bench scale (npm run bench -- properties: 6 000 cases) it takes ~30 s; 200 in the suite, < 2 s
});
