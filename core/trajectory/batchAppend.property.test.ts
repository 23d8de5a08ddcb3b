/**
 * The batch producer API (maxl.addSegmentsNow, maxl.addSegmentsToQueue) against the
 * single-move one it stands in for: the same moves, good and bad, must give the same
 * segments, the same plan and the same as-planned history to the bit, and the same
 * refusals (naming the move: `moves[i]…`), whether the queue keeps them as columns
 * or, with a listener, as objects; and a dry run that takes runs of final segments
 * (DryRun.takeWhileFull(run)) must lock what one taking a segment at a time locks,
 * behind the batch API and behind awaited single adds (the planner bench's two loops).
 */
import { describe, expect, it } from 'vitest';
import fc from 'fast-check';
import { createMAXL, type MaxlConfig, type Move } from '../index.ts';
import { queueOf, type Maxl } from '../maxl.ts';
import { MaxlError } from '../errors.ts';
import { DryRun } from './dryRun.ts';
import { historyOf, machine } from '../testing/maxlHistory.ts';

const LIMITS = { maxVelocity: 250, maxAcceleration: 3000, junctionDeviation: 0.05 };

const coord = fc.double({ min: -40, max: 40, noNaN: true });
/** Moves of every kind the queue takes, and some it refuses. */
const moveArb: fc.Arbitrary<Move> = fc.oneof(
  { weight: 20, arbitrary: fc.tuple(coord, coord).map((p): Move => ({ endPosition: p })) },
  {
    weight: 4,
    arbitrary: fc
      .record({ p: fc.tuple(coord, coord), v: fc.double({ min: 1, max: 400, noNaN: true }), a: fc.option(fc.double({ min: 100, max: 5000, noNaN: true })) })
      .map(({ p, v, a }): Move => (a === null ? { endPosition: p, maxVelocity: v } : { endPosition: p, maxVelocity: v, maxAcceleration: a })),
  },
  { weight: 2, arbitrary: fc.tuple(coord, coord, fc.constantFrom(0, 1)).map(([x, y, pen]): Move => ({ endPosition: [x, y], eventChannels: { pen } })) },
  { weight: 1, arbitrary: fc.double({ min: 0, max: 0.05, noNaN: true }).map((s): Move => ({ dwell_s: s })) },
  { weight: 1, arbitrary: coord.map((x): Move => ({ endPosition: { x } })) },
  { weight: 1, arbitrary: fc.constant<Move>({ endPosition: [0, 0] }) },
  // Refused: not a number, outside the soft limits, the wrong dimension, a bad cap.
  { weight: 1, arbitrary: fc.constantFrom<Move>({ endPosition: [Number.NaN, 0] }, { endPosition: [500, 0] }, { endPosition: [1] }, { endPosition: [1, 1], maxVelocity: -1 }) },
);

function config(corexy: boolean, capacity: number | null): MaxlConfig {
  return {
    motionAxes: ['x', 'y'],
    eventChannels: ['pen'],
    limits: LIMITS,
    softLimits: { x: [-100, 100], y: [-100, 100] },
    transforms: corexy ? [{ type: 'corexy', from: ['x', 'y'], to: ['a', 'b'] }] : [],
    ...(capacity === null ? {} : { queueCapacity: capacity }),
  };
}


/** The single-move producer loop: take until there is room, then append; a refused move is noted (its code) and skipped. */
function oneByOne(maxl: Maxl, moves: Move[]): string[] {
  const q = queueOf(maxl);
  const dry = new DryRun(q);
  const refused: string[] = [];
  moves.forEach((move, i) => {
    dry.takeWhileFull();
    try {
      q.append(move);
    } catch (err) {
      refused.push(`${i}:${(err as MaxlError).code}`);
    }
  });
  dry.finish();
  return refused;
}

/** The batch producer loop: runs of moves while there is room, a dry run taking runs of `run`; a refused move is noted and skipped. */
function inRuns(maxl: Maxl, moves: Move[], run: number): string[] {
  const dry = new DryRun(queueOf(maxl));
  const refused: string[] = [];
  let next = 0;
  while (next < moves.length) {
    try {
      next = maxl.addSegmentsNow(moves, next);
    } catch (err) {
      const e = err as MaxlError;
      // The error names the move it refused, and the moves before it are queued.
      const at = Number(/^moves\[(\d+)\]/.exec(e.field ?? '')?.[1]);
      expect(at).toBeGreaterThanOrEqual(next);
      refused.push(`${at}:${e.code}`);
      next = at + 1;
      continue;
    }
    dry.takeWhileFull(run);
  }
  dry.finish();
  return refused;
}

/**
 * The per-point producer loop of the planner bench (the paper's Listing 2): one awaited
 * addSegmentToQueue per move, a dry run taking runs of `run` after each; a refused move
 * is noted and skipped.
 */
async function perPointInRuns(maxl: Maxl, moves: Move[], run: number): Promise<string[]> {
  const dry = new DryRun(queueOf(maxl));
  const refused: string[] = [];
  for (let i = 0; i < moves.length; i++) {
    try {
      await maxl.addSegmentToQueue(moves[i]);
    } catch (err) {
      refused.push(`${i}:${(err as MaxlError).code}`);
    }
    dry.takeWhileFull(run);
  }
  dry.finish();
  return refused;
}

describe('a dry run taking runs of final segments behind awaited single adds', () => {
  it('locks, plans and records what one taking a segment at a time does, and refuses the same moves', async () => {
    await fc.assert(
      fc.asyncProperty(
        fc.boolean(),
        fc.boolean(),
        fc.option(fc.integer({ min: 1, max: 8 })),
        fc.integer({ min: 1, max: 10 }),
        fc.array(moveArb, { minLength: 1, maxLength: 80 }),
        async (corexy, listening, capacity, run, moves) => {
          const c = config(corexy, capacity);
          const single = machine(c, listening);
          const perPoint = machine(c, !listening);
          expect(await perPointInRuns(perPoint, moves, run)).toEqual(oneByOne(single, moves));
          expect(queueOf(perPoint).transmittedEnd_us).toBe(queueOf(single).transmittedEnd_us);
          expect(historyOf(perPoint)).toEqual(historyOf(single));
        },
      ),
      { numRuns: 150 },
    );
  });
});

describe('the batch producer API', () => {
  it('queues, plans and records moves exactly as single appends, and refuses the same ones', () => {
    fc.assert(
      fc.property(
        fc.boolean(),
        fc.boolean(),
        fc.option(fc.integer({ min: 1, max: 8 })),
        fc.integer({ min: 1, max: 10 }),
        fc.array(moveArb, { minLength: 1, maxLength: 80 }),
        (corexy, listening, capacity, run, moves) => {
          const c = config(corexy, capacity);
          const single = machine(c, listening);
          const batch = machine(c, !listening);
          expect(inRuns(batch, moves, run)).toEqual(oneByOne(single, moves));
          expect(queueOf(batch).skippedZeroLength).toBe(queueOf(single).skippedZeroLength);
          expect(queueOf(batch).transmittedEnd_us).toBe(queueOf(single).transmittedEnd_us);
          expect(historyOf(batch)).toEqual(historyOf(single));
          // The next move starts where the path ends, on its own copy of the last end.
          expect(batch.nextMoveStart).toEqual(single.nextMoveStart);
        },
      ),
      { numRuns: 200 },
    );
  });

  it('plans a fine path deeper than the capacity as single appends do, handing final segments over in runs', () => {
    // Steps of 1–50 µm at up to 250 mm/s: braking needs hundreds of them, more than the capacity,
    // so the batch producer may queue a run of final segments past what a single add could.
    const step = fc.record({ length: fc.double({ min: 0.001, max: 0.05, noNaN: true }), turn: fc.double({ min: -0.3, max: 0.3, noNaN: true }) });
    fc.assert(
      fc.property(fc.integer({ min: 8, max: 128 }), fc.integer({ min: 1, max: 64 }), fc.array(step, { minLength: 50, maxLength: 1500 }), (capacity, run, steps) => {
        let [x, y, heading] = [0, 0, 0];
        const moves: Move[] = steps.map(({ length, turn }) => {
          heading += turn;
          x += length * Math.cos(heading);
          y += length * Math.sin(heading);
          return { endPosition: [x, y] };
        });
        const c = config(false, capacity);
        const single = machine(c, false);
        const batch = machine(c, false);
        expect(inRuns(batch, moves, run)).toEqual(oneByOne(single, moves));
        expect(historyOf(batch)).toEqual(historyOf(single));
      }),
      { numRuns: 60 },
    );
  });

  it('at a lookahead deeper than the capacity, queues a run of final segments past braking depth, and no more, for single adds as for the batch', async () => {
    // 20 000 chords of 3 µm round a circle: braking from 250 mm/s needs ~3 500 of them.
    const r = (20_000 * 0.003) / (2 * Math.PI);
    const moves: Move[] = Array.from({ length: 20_000 }, (_, k) => {
      const theta = (2 * Math.PI * (k + 1)) / 20_000;
      return { endPosition: [r * Math.cos(theta), r * Math.sin(theta)] };
    });
    const c: MaxlConfig = { motionAxes: ['x', 'y'], limits: LIMITS, queueCapacity: 512 };
    const [braking, single, batch] = [0, 1, 2].map(() => createMAXL(c, { initialPosition: [r, 0] }));
    const [qr, qs, qb] = [braking, single, batch].map(queueOf);
    const [dr, ds, db] = [qr, qs, qb].map((q) => new DryRun(q));
    // Braking depth: an executor that takes every final segment past the capacity, so that none is held there.
    let brakingDepth = 0;
    for (const m of moves) {
      qr.append(m);
      brakingDepth = Math.max(brakingDepth, qr.untransmittedCount);
      while (qr.untransmittedCount >= qr.capacity && qr.frontIsFinal) dr.takeFront();
    }
    // Single adds, awaited, a dry run taking runs after each; the calls in which it took any segment.
    let deepestSingle = 0;
    let takingCalls = 0;
    for (const m of moves) {
      await single.addSegmentToQueue(m);
      deepestSingle = Math.max(deepestSingle, qs.untransmittedCount);
      const before = ds.segments;
      ds.takeWhileFull(64);
      if (ds.segments > before) takingCalls++;
    }
    let deepestBatch = 0;
    let calls = 0;
    for (let next = 0; next < moves.length; calls++) {
      next = batch.addSegmentsNow(moves, next);
      deepestBatch = Math.max(deepestBatch, qb.untransmittedCount);
      db.takeWhileFull(64);
    }
    dr.finish();
    ds.finish();
    db.finish();
    expect(brakingDepth).toBeGreaterThan(3000);
    expect(deepestSingle).toBeGreaterThan(brakingDepth);
    expect(deepestSingle).toBeLessThanOrEqual(brakingDepth + 512 / 8);
    expect(deepestBatch).toBe(deepestSingle);
    // Runs, not one segment (or one move) a call: producer and executor do not alternate per point.
    expect(takingCalls).toBeLessThan(moves.length / 32);
    expect(calls).toBeLessThan(moves.length / 32);
    // The same plan every way.
    expect(ds.duration_s).toBe(dr.duration_s);
    expect(db.duration_s).toBe(dr.duration_s);
    expect(historyOf(single)).toEqual(historyOf(braking));
    expect(historyOf(batch)).toEqual(historyOf(braking));
  });

  it('appends only while there is room, and returns where it stopped', () => {
    const maxl = machine(config(false, 4), false);
    const moves: Move[] = Array.from({ length: 10 }, (_, i) => ({ endPosition: [i + 1, 0] }));
    expect(maxl.addSegmentsNow(moves)).toBe(4);
    expect(maxl.addSegmentsNow(moves, 4)).toBe(4);
    new DryRun(queueOf(maxl)).takeFront();
    expect(maxl.addSegmentsNow(moves, 4)).toBe(5);
    expect(maxl.addSegmentsNow(moves, 10)).toBe(10);
    expect(() => maxl.addSegmentsNow(moves, 11)).toThrow(/from: must be an index from 0 to 10/);
    expect(() => maxl.addSegmentsNow('moves' as unknown as Move[])).toThrow(/moves: must be an array of moves/);
  });

  it('copies the last end position, so a caller reusing its arrays changes nothing queued', () => {
    const maxl = machine(config(false, null), false);
    const point = [1, 2];
    maxl.addSegmentsNow([{ endPosition: point }]);
    point[0] = 50;
    expect(maxl.nextMoveStart).toEqual([1, 2]);
    maxl.addSegmentsNow([{ endPosition: [3, 2] }]);
    expect(queueOf(maxl).segments().map((s) => s.start)).toEqual([[0, 0], [1, 2]]);
  });

  it('refuses a bad move by its index, with the moves before it queued and nothing of it', () => {
    const maxl = machine(config(false, null), false);
    const moves: Move[] = [{ endPosition: [1, 0] }, { endPosition: [2, 0] }, { endPosition: [2, Number.NaN] }, { endPosition: [3, 0] }];
    expect(() => maxl.addSegmentsNow(moves)).toThrow(new MaxlError('MOVE_INVALID', 'must be a finite number, got NaN', 'moves[2].endPosition[1]'));
    expect(queueOf(maxl).untransmittedCount).toBe(2);
    expect(maxl.nextMoveStart).toEqual([2, 0]);
  });

  it('leaves moves waiting for room to go first', async () => {
    const maxl = machine(config(false, 2), false);
    await maxl.addSegmentToQueue({ endPosition: [1, 0] });
    await maxl.addSegmentToQueue({ endPosition: [2, 0] });
    const waiting = maxl.addSegmentToQueue({ endPosition: [3, 0] });
    const dry = new DryRun(queueOf(maxl));
    dry.takeFront();
    expect(maxl.addSegmentsNow([{ endPosition: [9, 9] }])).toBe(0);
    await waiting;
    expect(maxl.nextMoveStart).toEqual([3, 0]);
  });

  it('refuses every call once the instance is closed', () => {
    const maxl = machine(config(false, null), false);
    maxl.close();
    expect(() => maxl.addSegmentsNow([{ endPosition: [1, 0] }])).toThrow(/QUEUE_CLOSED|closed/);
  });
});

describe('addSegmentsToQueue', () => {
  /** Takes a segment every turn of the event loop until `done` settles, as a slow executor would. */
  async function drainUntil(maxl: Maxl, done: Promise<unknown>): Promise<void> {
    let settled = false;
    void done.then(
      () => (settled = true),
      () => (settled = true),
    );
    const dry = new DryRun(queueOf(maxl));
    while (!settled) {
      await new Promise((r) => setTimeout(r, 0));
      dry.takeFront();
    }
  }

  it('waits for room as often as it must and queues every move in order', async () => {
    const moves: Move[] = Array.from({ length: 30 }, (_, i) => ({ endPosition: [i + 1, (i % 3) * 0.5] }));
    const batch = machine(config(false, 3), false);
    const done = batch.addSegmentsToQueue(moves);
    await drainUntil(batch, done);
    await expect(done).resolves.toBe(30);
    const single = machine(config(false, 3), false);
    for (const m of moves) queueOf(single).append(m);
    new DryRun(queueOf(batch)).finish();
    new DryRun(queueOf(single)).finish();
    expect(historyOf(batch).map((r) => r.start)).toEqual(historyOf(single).map((r) => r.start));
    expect(historyOf(batch).at(-1)?.end).toEqual([30, 1]);
  });

  it('rejects at a bad move with its index, the moves before it queued', async () => {
    const maxl = machine(config(false, 2), false);
    const moves: Move[] = [{ endPosition: [1, 0] }, { endPosition: [2, 0] }, { endPosition: [3, 0] }, { endPosition: [500, 0] }, { endPosition: [4, 0] }];
    const done = maxl.addSegmentsToQueue(moves);
    await drainUntil(maxl, done);
    await expect(done).rejects.toMatchObject({ code: 'SOFT_LIMIT', field: 'moves[3].endPosition.x' });
    expect(maxl.nextMoveStart).toEqual([3, 0]);
  });

  it('gives up the wait for room when its signal aborts', async () => {
    const maxl = machine(config(false, 2), false);
    const abort = new AbortController();
    const moves: Move[] = Array.from({ length: 5 }, (_, i) => ({ endPosition: [i + 1, 0] }));
    const done = maxl.addSegmentsToQueue(moves, { signal: abort.signal });
    abort.abort();
    await expect(done).rejects.toMatchObject({ code: 'ABORTED' });
    expect(maxl.nextMoveStart).toEqual([2, 0]);
    expect(queueOf(maxl).untransmittedCount).toBe(2);
  });
});
