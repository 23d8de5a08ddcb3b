/**
 * Property tests of the planner over random polylines and limits (fast-check).
 * Each property is checked on the output of planPath, which uses the same
 * lookahead as the queue.
 */
import { describe, expect, it } from 'vitest';
import fc from 'fast-check';
import { createMAXL, planPath, type LimitsConfig, type PathMove } from '../index.ts';
import { resolveLimits } from '../config/limits.ts';
import { refDuration, refBlocks, refJunctionSpeeds2, refJunctionCap2, type RefLimits } from '../testing/referencePlanner.ts';
import { queueOf } from '../maxl.ts';

const REL = 1e-9;

/** Random limits: a scalar, per-axis arrays, or both. */
function limitsArb(axes: number): fc.Arbitrary<LimitsConfig> {
  const speed = fc.double({ min: 5, max: 500, noNaN: true });
  const accel = fc.double({ min: 50, max: 20000, noNaN: true });
  const perAxis = (arb: fc.Arbitrary<number>) => fc.array(arb, { minLength: axes, maxLength: axes });
  return fc.record({
    kind: fc.constantFrom('scalar', 'axis', 'both'),
    v: speed,
    a: accel,
    va: perAxis(speed),
    aa: perAxis(accel),
    jd: fc.double({ min: 0.001, max: 1, noNaN: true }),
  }).map(({ kind, v, a, va, aa, jd }) => {
    const l: LimitsConfig = { junctionDeviation: jd };
    if (kind !== 'axis') {
      l.maxVelocity = v;
      l.maxAcceleration = a;
    }
    if (kind !== 'scalar') {
      l.axisMaxVelocity = va;
      l.axisMaxAcceleration = aa;
    }
    return l;
  });
}

/** Random polylines mixing long moves, tiny steps, repeats (zero length), straight runs and reversals. */
function pathArb(axes: number): fc.Arbitrary<{ points: number[][]; speeds: (number | undefined)[] }> {
  const coord = fc.double({ min: -100, max: 100, noNaN: true });
  const step = fc.oneof(
    fc.array(coord, { minLength: axes, maxLength: axes }).map((p) => ({ kind: 'abs' as const, p })),
    fc.array(fc.double({ min: -0.05, max: 0.05, noNaN: true }), { minLength: axes, maxLength: axes }).map((p) => ({ kind: 'rel' as const, p })),
    fc.constant({ kind: 'repeat' as const, p: [] as number[] }),
    fc.constant({ kind: 'reverse' as const, p: [] as number[] }),
    fc.double({ min: 0.1, max: 3, noNaN: true }).map((f) => ({ kind: 'extend' as const, p: [f] })),
  );
  return fc
    .record({
      start: fc.array(coord, { minLength: axes, maxLength: axes }),
      steps: fc.array(fc.record({ step, speed: fc.option(fc.double({ min: 1, max: 400, noNaN: true }), { nil: undefined }) }), { minLength: 1, maxLength: 25 }),
    })
    .map(({ start, steps }) => {
      const points = [start];
      const speeds: (number | undefined)[] = [];
      for (const { step: s, speed } of steps) {
        const last = points[points.length - 1];
        const prev = points[points.length - 2] ?? last;
        let next: number[];
        if (s.kind === 'abs') next = s.p;
        else if (s.kind === 'rel') next = last.map((v, i) => v + s.p[i]);
        else if (s.kind === 'repeat') next = [...last];
        else if (s.kind === 'reverse') next = [...prev];
        else next = last.map((v, i) => v + (v - prev[i]) * s.p[0]);
        points.push(next);
        speeds.push(speed);
      }
      return { points, speeds };
    });
}

function resolved(limits: LimitsConfig, axes: number): RefLimits {
  return resolveLimits(limits, axes);
}

function plan(points: number[][], speeds: (number | undefined)[], limits: LimitsConfig) {
  return planPath(points[0], points.slice(1).map((end, i) => ({ end, maxVelocity: speeds[i] })), limits);
}

type PlannedSegment = ReturnType<typeof plan>['segments'][number];

/** Calls `check` for every phase of every segment, with the segment's unit direction. */
function eachPhase(p: ReturnType<typeof plan>, check: (seg: PlannedSegment, unit: number[], ph: PlannedSegment['phases'][number]) => void): void {
  for (const seg of p.segments) {
    const unit = seg.end.map((v, i) => (v - seg.start[i]) / seg.length);
    for (const ph of seg.phases) check(seg, unit, ph);
  }
}

describe.each([2, 3])('planPath properties in %i axes', (axes) => {
  const input = fc.record({ path: pathArb(axes), limits: limitsArb(axes) });

  it('never exceeds a speed limit: magnitude, per axis, or the move cap', () => {
    fc.assert(
      fc.property(input, ({ path, limits }) => {
        const p = plan(path.points, path.speeds, limits);
        const l = resolved(limits, axes);
        eachPhase(p, (seg, unit, ph) => {
          for (const v of [ph.v0, ph.v0 + ph.a0 * ph.duration]) {
            const tol = 1e-9 * (1 + Math.abs(v));
            expect(v).toBeGreaterThanOrEqual(-tol);
            expect(v).toBeLessThanOrEqual(l.maxSpeed + tol);
            expect(v).toBeLessThanOrEqual(seg.cruiseLimit + tol);
            unit.forEach((u, i) => expect(Math.abs(u * v)).toBeLessThanOrEqual(l.axisMaxSpeed[i] + tol));
          }
        });
        // The move caps, checked from the input rather than from the plan.
        const blocks = refBlocks(path.points, l, path.speeds.map((s) => s ?? Infinity));
        p.segments.forEach((seg, k) => expect(seg.peakVelocity).toBeLessThanOrEqual(blocks[k].cruise * (1 + REL) + 1e-12));
      }),
    );
  });

  it('never exceeds the acceleration limit projected on each segment', () => {
    fc.assert(
      fc.property(input, ({ path, limits }) => {
        const p = plan(path.points, path.speeds, limits);
        const l = resolved(limits, axes);
        eachPhase(p, (seg, unit, ph) => {
          const a = Math.abs(ph.a0);
          const tol = 1e-9 * (1 + a);
          expect(a).toBeLessThanOrEqual(seg.accelerationLimit + tol);
          expect(a).toBeLessThanOrEqual(l.maxAccel + tol);
          unit.forEach((u, i) => expect(Math.abs(u * a)).toBeLessThanOrEqual(l.axisMaxAccel[i] + tol));
        });
      }),
    );
  });

  it('keeps speed continuous at junctions and within the junction-deviation bound', () => {
    fc.assert(
      fc.property(input, ({ path, limits }) => {
        const p = plan(path.points, path.speeds, limits);
        const l = resolved(limits, axes);
        const blocks = refBlocks(path.points, l, path.speeds.map((s) => s ?? Infinity));
        expect(p.segments.length).toBe(blocks.length);
        for (let k = 0; k + 1 < p.segments.length; k++) {
          const out = p.segments[k];
          const into = p.segments[k + 1];
          const last = out.phases[out.phases.length - 1];
          const endSpeed = last.v0 + last.a0 * last.duration;
          expect(endSpeed).toBeCloseTo(into.phases[0].v0, 6);
          expect(out.exitVelocity).toBe(into.entryVelocity);
          const cap2 = refJunctionCap2(blocks[k], blocks[k + 1], l);
          expect(into.entryVelocity ** 2).toBeLessThanOrEqual(cap2 * (1 + 1e-9) + 1e-9);
        }
      }),
    );
  });

  it('passes through every vertex and ends at rest', () => {
    fc.assert(
      fc.property(input, ({ path, limits }) => {
        const p = plan(path.points, path.speeds, limits);
        // The distinct vertices, in order (zero-length moves add none).
        const vertices = [path.points[0]];
        for (const q of path.points.slice(1)) {
          const last = vertices[vertices.length - 1];
          if (Math.hypot(...q.map((v, i) => v - last[i])) >= 1e-9) vertices.push(q);
        }
        expect(p.segments.length).toBe(vertices.length - 1);
        p.segments.forEach((seg, k) => {
          const at = p.sample(seg.startTime);
          at.position.forEach((v, i) => expect(v).toBeCloseTo(vertices[k][i], 6));
          seg.end.forEach((v, i) => expect(v).toBe(vertices[k + 1][i]));
          const endOfSeg = p.sample(seg.startTime + seg.duration);
          endOfSeg.position.forEach((v, i) => expect(v).toBeCloseTo(vertices[k + 1][i], 6));
        });
        const end = p.sample(p.duration);
        end.position.forEach((v, i) => expect(v).toBeCloseTo(vertices[vertices.length - 1][i], 9));
        end.velocity.forEach((v) => expect(Math.abs(v)).toBeLessThanOrEqual(1e-9));
        if (p.segments.length > 0) {
          expect(p.segments[0].entryVelocity).toBe(0);
          expect(p.segments[p.segments.length - 1].exitVelocity).toBe(0);
        }
      }),
    );
  });

  it('is time-optimal: matches an independent O(n²) batch planner', () => {
    fc.assert(
      fc.property(input, ({ path, limits }) => {
        const p = plan(path.points, path.speeds, limits);
        const l = resolved(limits, axes);
        const speeds = path.speeds.map((s) => s ?? Infinity);
        const blocks = refBlocks(path.points, l, speeds);
        const e = refJunctionSpeeds2(blocks, l);
        p.segments.forEach((seg, k) => {
          expect(seg.entryVelocity ** 2).toBeCloseTo(e[k], 6);
        });
        const reference = refDuration(path.points, l, speeds);
        // Rounding in two independent float64 computations stays far below 1e-8; a
        // misjudged junction or a missed constraint shows up far above it.
        expect(Math.abs(p.duration - reference)).toBeLessThanOrEqual(1e-8 * (1 + reference));
      }),
    );
  });
});

/**
 * Dwells: a path cut by dwells is planned as its pieces, each from rest to rest.
 * The reference plans every piece between dwells on its own (the O(n²) planner),
 * so a dwell that let speed through, or a planner that stopped anywhere else,
 * shows in the total.
 */
describe.each([2, 3])('planPath with dwells in %i axes', (axes) => {
  const dwellArb = fc.oneof(fc.constant(0), fc.double({ min: 0, max: 2, noNaN: true }));
  const input = fc.record({
    path: pathArb(axes),
    limits: limitsArb(axes),
    // After which moves a dwell comes (indices may repeat: dwells in a row), and how long each is.
    dwells: fc.array(fc.record({ after: fc.nat(30), seconds: dwellArb }), { maxLength: 6 }),
  });

  /**
   * The moves with the dwells among them, and what the plan must be. A move shorter than
   * 1e-9 mm from the last kept point adds nothing (moves.ts ZERO_LENGTH_MM), so the machine
   * is still at that point when the next dwell comes: the dwell holds there (`holds`), and
   * the piece after it starts there, not at the dropped move's end (which can be up to
   * 1e-9 mm away: enough to turn a later sub-nm move into a kept one, or back).
   */
  function withDwells(path: { points: number[][]; speeds: (number | undefined)[] }, dwells: { after: number; seconds: number }[]) {
    const moves: PathMove[] = [];
    /** The pieces between dwells, as point lists and speeds, for the reference. */
    const pieces: { points: number[][]; speeds: (number | undefined)[] }[] = [{ points: [path.points[0]], speeds: [] }];
    /** Where each dwell holds, in order. */
    const holds: number[][] = [];
    let kept = path.points[0];
    const dwellsAt = (k: number) => dwells.filter((d) => Math.min(d.after, path.points.length - 1) === k);
    const addDwells = (k: number) => {
      for (const d of dwellsAt(k)) {
        moves.push({ dwell_s: d.seconds });
        holds.push(kept);
        pieces.push({ points: [kept], speeds: [] });
      }
    };
    addDwells(0);
    for (let k = 1; k < path.points.length; k++) {
      moves.push({ end: path.points[k], maxVelocity: path.speeds[k - 1] });
      const piece = pieces[pieces.length - 1];
      piece.points.push(path.points[k]);
      piece.speeds.push(path.speeds[k - 1]);
      if (Math.hypot(...path.points[k].map((v, i) => v - kept[i])) >= 1e-9) kept = path.points[k];
      addDwells(k);
    }
    return { moves, pieces, holds, total: dwells.reduce((t, d) => t + d.seconds, 0) };
  }

  it('rests before and after every dwell, holds there for exactly its time, and is optimal between', () => {
    fc.assert(
      fc.property(input, ({ path, limits, dwells }) => {
        const { moves, pieces, holds, total } = withDwells(path, dwells);
        const p = planPath(path.points[0], moves, limits);
        const l = resolved(limits, axes);
        const lines = p.segments.filter((s) => !s.dwell);
        expect(p.segments.length - lines.length).toBe(dwells.length);
        // Each dwell holds at the last point the path kept before it.
        expect(p.segments.filter((s) => s.dwell).map((s) => s.start)).toEqual(holds);
        for (const [k, seg] of p.segments.entries()) {
          if (!seg.dwell) continue;
          expect(seg.length).toBe(0);
          expect(seg.end).toEqual(seg.start);
          expect(seg.entryVelocity).toBe(0);
          expect(seg.exitVelocity).toBe(0);
          expect(seg.peakVelocity).toBe(0);
          if (k > 0) expect(p.segments[k - 1].exitVelocity).toBe(0);
          if (k + 1 < p.segments.length) expect(p.segments[k + 1].entryVelocity).toBe(0);
          // It holds its position, at rest, throughout.
          for (const f of [0, 0.5, 1]) {
            const s = p.sample(seg.startTime + f * seg.duration);
            s.position.forEach((v, i) => expect(v).toBeCloseTo(seg.start[i], 9));
            s.velocity.forEach((v) => expect(Math.abs(v)).toBe(0));
          }
        }
        // Exact dwell times, in order.
        const planned = p.segments.filter((s) => s.dwell).map((s) => s.duration);
        expect(planned).toEqual(moves.flatMap((m) => ('dwell_s' in m ? [m.dwell_s] : [])));
        // Optimal between dwells: each piece from rest to rest, by the reference planner.
        const reference = pieces.reduce((t, piece) => t + refDuration(piece.points, l, piece.speeds.map((s) => s ?? Infinity)), total);
        expect(Math.abs(p.duration - reference)).toBeLessThanOrEqual(1e-8 * (1 + reference));
      }),
    );
  });

  it('applies the queue’s duration floor: the same durations as the queue on that link', () => {
    fc.assert(
      fc.property(input, fc.double({ min: 0, max: 20_000, noNaN: true }), ({ path, limits, dwells }, floor_us) => {
        const { moves } = withDwells(path, dwells);
        const p = planPath(path.points[0], moves, limits, { minSegment_us: floor_us });
        for (const seg of p.segments) if (!seg.dwell) expect(seg.duration).toBeGreaterThanOrEqual(floor_us * 1e-6 * (1 - 1e-9));
        // The queue, given the same floor and the same moves, plans the same segments.
        const axisNames = path.points[0].map((_, i) => `a${i}`);
        const maxl = createMAXL({ motionAxes: axisNames, limits }, { initialPosition: path.points[0] });
        queueOf(maxl).setMinSegmentDuration(floor_us * 1e-6);
        for (const m of moves) queueOf(maxl).append('dwell_s' in m ? { dwell_s: m.dwell_s } : { endPosition: m.end, maxVelocity: m.maxVelocity });
        queueOf(maxl).planToRest();
        const queued = queueOf(maxl).segments();
        expect(queued.map((s) => s.duration_s)).toEqual(p.segments.map((s) => s.duration));
      }),
    );
  });
});
