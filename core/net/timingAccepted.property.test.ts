/**
 * Every TIMING the author sends is one the reader accepts.
 *
 * The planner plans short moves under random limits (machine and per-move caps,
 * dwells between them); the segments are encoded as the streamer encodes them
 * (timedPath.ts: runs of contiguous segments, each pump with the clock model as
 * refitted since, a shifted offset and rate) and fed, frame by frame, to the real
 * reader firmware (the Stepper example in wasm). Every frame must be acked.
 *
 * This reproduced the intermittent `MALFORMED, detail 6` of plotting: a clock
 * correction absorbed by lengthening the cruise of a segment that starts or ends
 * at rest made the device's entry or exit speed negative (segmentEncoding.ts
 * timingEntry says why, and how much a cruise may now absorb).
 */
import { existsSync } from 'node:fs';
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { createMAXL, type Move } from '../index.ts';
import { queueOf } from '../maxl.ts';
import { PUBLIC_FIRMWARE_DIR } from '../sim/device/nodeWasmLoader.ts';
import { DirectReader } from '../sim/testing/directReader.ts';
import type { Segment } from '../trajectory/segment.ts';
import { ClockMap } from './clockMap.ts';
import { NackReason } from './protocol.ts';
import { geometryMessages, timingEntry } from './segmentEncoding.ts';
import { timingForPath, type TimedPathEnd } from './timedPath.ts';

const built = existsSync(`${PUBLIC_FIRMWARE_DIR}Stepper.wasm`);

/** Spread evenly over decades, so slow and fast machines are both tried. */
const logUniform = (min: number, max: number) => fc.double({ min: Math.log10(min), max: Math.log10(max), noNaN: true }).map((u) => 10 ** u);
const limits = fc.record({
  maxVelocity: logUniform(1, 500),
  maxAcceleration: logUniform(10, 20_000),
  junctionDeviation: logUniform(0.001, 0.5),
});
const step = fc.tuple(fc.boolean(), logUniform(0.001, 20)).map(([back, d]) => (back ? -d : d));
const move: fc.Arbitrary<{ dx: number; dy: number; cap?: number } | { dwell: number }> = fc.oneof(
  // Along x, often reversing (the path comes to rest), or anywhere in the plane.
  { weight: 3, arbitrary: fc.record({ dx: step, dy: fc.constant(0), cap: fc.option(logUniform(0.5, 100), { nil: undefined }) }) },
  { weight: 3, arbitrary: fc.record({ dx: step, dy: step, cap: fc.option(logUniform(0.5, 500), { nil: undefined }) }) },
  { weight: 1, arbitrary: fc.record({ dwell: fc.double({ min: 0, max: 0.05, noNaN: true }) }) },
);
/** The clock model at each pump: offset from the truth (µs) and rate error. */
const model = fc.record({ offset: fc.double({ min: -200, max: 200, noNaN: true }), ppm: fc.double({ min: -300, max: 300, noNaN: true }) });

describe.skipIf(!built)(`TIMING the reader accepts${built ? '' : ' (skipped: Stepper.wasm not built)'}`, () => {
  it('every planned segment, encoded as the streamer does under a moving clock model, is acked by the real firmware', async () => {
    const reader = await DirectReader.stepper();
    const slots = [{ space: 'motion' as const, index: 0 }];
    fc.assert(
      fc.property(limits, fc.array(move, { minLength: 1, maxLength: 10 }), fc.array(model, { minLength: 12, maxLength: 12 }), fc.array(fc.integer({ min: 1, max: 3 }), { minLength: 12, maxLength: 12 }), fc.array(fc.oneof(fc.constant(0), fc.double({ min: 0, max: 400, noNaN: true })), { minLength: 12, maxLength: 12 }), (machine, moves, models, pumps, gaps) => {
        const maxl = createMAXL({ motionAxes: ['x', 'y'], limits: machine });
        let x = 0;
        let y = 0;
        for (const m of moves) {
          const next: Move = 'dwell' in m ? { dwell_s: m.dwell } : { endPosition: [(x += m.dx), (y += m.dy)], maxVelocity: m.cap };
          queueOf(maxl).append(next);
        }
        queueOf(maxl).planToRest();
        const segments: Segment[] = [];
        // After rest, the next segment may start a little later than the path ended (a new run, with its own start).
        let earliest = 100_000;
        for (let s = queueOf(maxl).transmitNext(earliest); s; s = queueOf(maxl).transmitNext(earliest)) {
          segments.push(s);
          earliest = s.endTime_us + gaps[segments.length % gaps.length];
        }
        if (segments.length === 0) return;

        // A fresh queue on the device, then the geometry, then the timing pump by pump.
        expect(reader.send({ type: 'HALT', mode: 0, at: 0 }, 0)).toEqual({ type: 'ACK' });
        for (const g of geometryMessages(segments, slots, 0, true)) expect(reader.send(g, 0)).toEqual({ type: 'ACK' });
        const path: TimedPathEnd = { timedEnd: null, timedEndAuthor: NaN };
        let i = 0;
        for (let pump = 0; i < segments.length; pump++) {
          const batch = segments.slice(i, i + pumps[pump % pumps.length]);
          const { offset, ppm } = models[pump % models.length];
          const clock = new ClockMap(0, offset, 1 + ppm * 1e-6);
          const { messages } = timingForPath(path, batch, clock, (seg) => segments.indexOf(seg), machine.maxAcceleration);
          for (const m of messages) {
            const answer = reader.send(m, 0);
            if (answer.type !== 'ACK') {
              const reason = Object.entries(NackReason).find(([, code]) => answer.type === 'NACK' && code === answer.reason)?.[0];
              expect.fail(`${m.type} of segments ${m.firstId}…${m.firstId + m.count - 1} refused: ${reason} ${JSON.stringify(answer)}, ${JSON.stringify(m.segments)}`);
            }
          }
          i += batch.length;
        }
      }),
    );
  }, 600_000); // at bench scale (npm run bench -- properties: 6 000 cases) it takes ~30 s; 200 in the suite, < 2 s

  it('a cruise that follows rest absorbs no clock correction; a dwell absorbs it without moving', () => {
    // A 10 mm move from rest to rest: accelerate, cruise, decelerate.
    const maxl = createMAXL({ motionAxes: ['x'], limits: { maxVelocity: 20, maxAcceleration: 200, junctionDeviation: 0.05 } });
    queueOf(maxl).append({ endPosition: [10] });
    queueOf(maxl).append({ dwell_s: 1 });
    queueOf(maxl).planToRest();
    const move = queueOf(maxl).transmitNext(0)!;
    const dwell = queueOf(maxl).transmitNext(0)!;
    const clock = new ClockMap(0, 0, 1);
    const late = new ClockMap(0, 100, 1); // the model has moved 100 µs since the chain began
    const plain = timingEntry(move, clock, 0);
    const corrected = timingEntry(move, late, 0);
    expect(corrected.entry.durations).toEqual(plain.entry.durations);
    // The dwell that follows takes the correction: 0.5 % of 1 s covers 100 µs.
    const held = timingEntry(dwell, late, plain.end);
    expect(held.entry.durations).toEqual([1_000_000 + 100]);
  });
});
