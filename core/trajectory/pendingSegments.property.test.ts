/**
 * The queue's columnar tail (pendingSegments.ts) against the object path it stands
 * in for: two machines get the same random operations, one with a queue listener
 * (which keeps every segment an object, as before the columnar store) and one with
 * none (columnar wherever it can be). Appends, dwells, zero-length moves, moves that
 * set events, speed and acceleration caps, single adds through the fast path, dry-run
 * locks (one at a time and in runs), reads of the queue (which
 * turn the columnar tail into objects mid-way), replaces and cancels must give the
 * same segments, the same receipts and errors, and the same as-planned history, to
 * the bit.
 */
import { describe, expect, it } from 'vitest';
import fc from 'fast-check';
import { createMAXL, type MaxlConfig, type Move } from '../index.ts';
import { queueOf, type Maxl } from '../maxl.ts';
import { DryRun } from './dryRun.ts';
import { historyOf, machine } from '../testing/maxlHistory.ts';
import type { Segment } from './segment.ts';

type Op =
  | { kind: 'line'; to: [number, number]; maxVelocity: number | null; maxAcceleration: number | null; pen: number | null; fast: boolean }
  | { kind: 'dwell'; s: number }
  | { kind: 'again' }
  | { kind: 'take'; n: number }
  | { kind: 'drain'; chunk: number }
  | { kind: 'read' }
  | { kind: 'replace'; k: number; to: [number, number] }
  | { kind: 'cancel'; k: number };

const coord = fc.double({ min: -40, max: 40, noNaN: true });
const opArb: fc.Arbitrary<Op> = fc.oneof(
  { weight: 12, arbitrary: fc.record({
    kind: fc.constant('line' as const),
    to: fc.tuple(coord, coord),
    maxVelocity: fc.option(fc.double({ min: 1, max: 400, noNaN: true })),
    maxAcceleration: fc.option(fc.double({ min: 100, max: 5000, noNaN: true })),
    pen: fc.option(fc.constantFrom(0, 1), { freq: 6 }),
    // Through a single add's fast path (appendIfPlainLine: a plain line, nobody listening) where it applies.
    fast: fc.boolean(),
  }) },
  { weight: 1, arbitrary: fc.record({ kind: fc.constant('dwell' as const), s: fc.double({ min: 0, max: 0.05, noNaN: true }) }) },
  { weight: 1, arbitrary: fc.record({ kind: fc.constant('again' as const) }) },
  { weight: 4, arbitrary: fc.record({ kind: fc.constant('take' as const), n: fc.integer({ min: 1, max: 6 }) }) },
  { weight: 2, arbitrary: fc.record({ kind: fc.constant('drain' as const), chunk: fc.constantFrom(1, 2, 4) }) },
  { weight: 1, arbitrary: fc.record({ kind: fc.constant('read' as const) }) },
  { weight: 1, arbitrary: fc.record({ kind: fc.constant('replace' as const), k: fc.nat(8), to: fc.tuple(coord, coord) }) },
  { weight: 1, arbitrary: fc.record({ kind: fc.constant('cancel' as const), k: fc.nat(8) }) },
);

const LIMITS = { maxVelocity: 250, maxAcceleration: 3000, junctionDeviation: 0.05 };

function moveOf(op: Extract<Op, { kind: 'line' }>): Move {
  const move: Move = { endPosition: op.to };
  if (op.maxVelocity !== null) move.maxVelocity = op.maxVelocity;
  if (op.maxAcceleration !== null) move.maxAcceleration = op.maxAcceleration;
  if (op.pen !== null) move.eventChannels = { pen: op.pen };
  return move;
}

/** What a segment is, as far as anyone can tell from outside: every field but those that are working values while unplanned. */
function describeSegment(seg: Segment) {
  const settled = seg.state !== 'unplanned';
  return {
    id: seg.id,
    moveId: seg.moveId,
    state: seg.state,
    start: seg.start,
    end: seg.end,
    unit: seg.unit,
    length: seg.length,
    moveOffset: seg.moveOffset,
    dwell_s: seg.dwell_s,
    actuatorStart: seg.actuatorStart,
    actuatorRate: seg.actuatorRate,
    accel: seg.accel,
    cruise2: seg.cruise2,
    maxEntry2: seg.maxEntry2,
    entry2: settled ? seg.entry2 : null,
    exit2: settled ? seg.exit2 : null,
    timing: settled ? seg.timing : null,
    duration_s: settled ? seg.duration_s : null,
    startTime_us: seg.startTime_us,
    eventsAtStart: seg.eventsAtStart,
    source: { end: seg.source.end, maxVelocity: seg.source.maxVelocity, maxAcceleration: seg.source.maxAcceleration, events: seg.source.events, actuatorEnd: seg.source.actuatorEnd },
  };
}

/** Runs one operation; returns what a caller sees of it (a receipt, a duration, or an error code). */
function apply(maxl: Maxl, op: Op): unknown {
  const q = queueOf(maxl);
  try {
    switch (op.kind) {
      case 'line':
        return op.fast ? (q.appendIfPlainLine(moveOf(op)) ?? q.append(moveOf(op))) : q.append(moveOf(op));
      case 'dwell':
        return q.append({ dwell_s: op.s });
      case 'again':
        return q.append({ endPosition: [...q.tailPosition] });
      case 'take': {
        const durations: number[] = [];
        for (let i = 0; i < op.n; i++) durations.push(q.executeFrontNow(0));
        return durations;
      }
      case 'drain': {
        // What a producer loop's executor does after each add: take segments (final ones, past the capacity) until there is
        // room, then (chunk > 1, as for a batch producer) a run of final ones (executeFinalRun without a listener).
        const dry = new DryRun(q);
        dry.takeWhileFull(op.chunk);
        return [dry.segments, dry.duration_s];
      }
      case 'read':
        return q.segments().map(describeSegment);
      case 'replace':
      case 'cancel': {
        const ahead = q.segments().filter((s) => s.state === 'unplanned' || s.state === 'planned');
        if (ahead.length === 0) return 'nothing ahead';
        const moveId = ahead[op.k % ahead.length].moveId;
        if (op.kind === 'cancel') return maxl.cancelMove(moveId);
        return maxl.replaceMove(moveId, { endPosition: op.to });
      }
    }
  } catch (err) {
    return { error: (err as { code?: string }).code ?? String(err) };
  }
}


describe('the queue keeps untransmitted lines as columns', () => {
  it('and plans, locks, edits and records them exactly as segment objects', () => {
    fc.assert(
      // A small queue capacity makes the lookahead hold segments past it while the front is not final, and drains lock only final ones.
      fc.property(fc.boolean(), fc.option(fc.integer({ min: 1, max: 6 })), fc.array(opArb, { minLength: 1, maxLength: 60 }), (corexy, capacity, ops) => {
        const config: MaxlConfig = {
          motionAxes: ['x', 'y'],
          eventChannels: ['pen'],
          limits: LIMITS,
          transforms: corexy ? [{ type: 'corexy', from: ['x', 'y'], to: ['a', 'b'] }] : [],
          ...(capacity === null ? {} : { queueCapacity: capacity }),
        };
        const objects = machine(config, true);
        const columns = machine(config, false);
        for (const op of ops) {
          const expected = apply(objects, op);
          const actual = apply(columns, op);
          expect(actual).toEqual(expected);
          expect(queueOf(columns).untransmittedCount).toBe(queueOf(objects).untransmittedCount);
          expect(queueOf(columns).transmittedEnd_us).toBe(queueOf(objects).transmittedEnd_us);
          expect(queueOf(columns).skippedZeroLength).toBe(queueOf(objects).skippedZeroLength);
        }
        const dryObjects = new DryRun(queueOf(objects));
        const dryColumns = new DryRun(queueOf(columns));
        dryObjects.finish();
        dryColumns.finish();
        expect(dryColumns.segments).toBe(dryObjects.segments);
        expect(dryColumns.duration_s).toBe(dryObjects.duration_s);
        expect(historyOf(columns)).toEqual(historyOf(objects));
        expect(queueOf(columns).segments().map(describeSegment)).toEqual(queueOf(objects).segments().map(describeSegment));
      }),
      { numRuns: 150 },
    );
  });

  it('leaves nothing columnar once someone listens, and a listener hears every segment as one object', () => {
    const maxl = machine({ motionAxes: ['x', 'y'], limits: LIMITS }, false);
    const q = queueOf(maxl);
    for (let i = 1; i <= 20; i++) q.append({ endPosition: [i, (i % 2) * 0.5] });
    const seen = new Map<number, Segment>();
    maxl.queue.subscribe((e) => {
      for (const s of e.segments) {
        const before = seen.get(s.id);
        if (before) expect(s).toBe(before);
        seen.set(s.id, s as Segment);
      }
    });
    const held = q.segments();
    expect(held.map((s) => s.id)).toEqual(Array.from({ length: 20 }, (_, i) => i + 1));
    q.append({ endPosition: [21, 0] });
    new DryRun(q).finish();
    // Every segment made before the listener came is the very object it hears of when it is sent.
    for (const s of held) expect(seen.get(s.id)).toBe(s);
    expect(maxl.history.size).toBe(21);
  });
});
