import { describe, expect, it } from 'vitest';
import fc from 'fast-check';
import { createMAXL, type MaxlConfig, type TransformConfig } from '../index.ts';
import { queueOf } from '../maxl.ts';

const limits = { maxVelocity: 200, maxAcceleration: 2000 };
const machine = (transforms: TransformConfig[]): MaxlConfig => ({ motionAxes: ['x', 'y'], limits, transforms });

/** Every actuator track along every transmitted segment, sampled densely, against the exact transform. */
function worstActuatorError(cfg: MaxlConfig, exact: (p: number[]) => number[], path: number[][], start = [0, 0]) {
  const maxl = createMAXL(cfg, { initialPosition: start });
  for (const p of path) queueOf(maxl).append({ endPosition: p });
  queueOf(maxl).planToRest();
  let worst = 0;
  let segments = 0;
  for (let seg = queueOf(maxl).transmitNext(0); seg; seg = queueOf(maxl).transmitNext(0)) {
    segments++;
    for (let k = 0; k <= 64; k++) {
      const t = seg.startTime_us + ((seg.endTime_us - seg.startTime_us) * k) / 64;
      const s = maxl.sample(t);
      const want = exact(s.position);
      s.actuator.forEach((v, j) => (worst = Math.max(worst, Math.abs(v - want[j]))));
    }
  }
  return { worst, segments, maxl };
}

describe('transforms', () => {
  it('CoreXY: a = x + y, b = x − y, exactly, as tracks', () => {
    const { worst, segments, maxl } = worstActuatorError(
      machine([{ type: 'corexy', from: ['x', 'y'], to: ['a', 'b'] }]),
      ([x, y]) => [x + y, x - y],
      [[100, 0], [100, 50], [-20, 70]],
    );
    expect(segments).toBe(3); // linear: never subdivided
    expect(worst).toBeLessThan(1e-9);
    const end = maxl.sample(1e12);
    expect(end.actuator).toEqual([50, -90]);
    expect(maxl.trackValue('a', 1e12)).toBe(50);
    expect(maxl.trackValue('b', 1e12)).toBe(-90);
    expect(maxl.trackValue('x', 1e12)).toBe(-20);
  });

  it('H-bot shares the CoreXY kinematics', () => {
    const { worst } = worstActuatorError(machine([{ type: 'hbot', from: ['x', 'y'], to: ['l', 'r'] }]), ([x, y]) => [x + y, x - y], [[30, 40]]);
    expect(worst).toBeLessThan(1e-9);
  });

  it('a linear map given as a matrix, including more outputs than inputs', () => {
    const m = [
      [2, 0],
      [0.5, -1],
      [1, 1],
    ];
    const { worst, segments } = worstActuatorError(
      machine([{ type: 'linear', from: ['y', 'x'], to: ['p', 'q', 'r'], matrix: m }]),
      ([x, y]) => m.map((row) => row[0] * y + row[1] * x),
      [[10, 10], [-5, 20]],
    );
    expect(segments).toBe(2);
    expect(worst).toBeLessThan(1e-9);
  });

  it('a custom function declared linear is not subdivided', () => {
    const { worst, segments } = worstActuatorError(
      machine([{ type: 'function', from: ['x', 'y'], to: ['u'], fn: ([x, y]) => [3 * x - y], linear: true }]),
      ([x, y]) => [3 * x - y],
      [[40, 10]],
    );
    expect(segments).toBe(1);
    expect(worst).toBeLessThan(1e-9);
  });

  it('polar (nonlinear): lines are subdivided so every actuator stays within the tolerance', () => {
    const polar = ([x, y]: readonly number[]) => [Math.hypot(x, y), Math.atan2(y, x) * 50]; // θ as 50 mm of arc per radian
    fc.assert(
      fc.property(
        fc.array(fc.tuple(fc.double({ min: 5, max: 100, noNaN: true }), fc.double({ min: -1.2, max: 1.2, noNaN: true })), { minLength: 1, maxLength: 6 }),
        fc.constantFrom(0.01, 0.05, 0.002),
        (polarPoints, tolerance) => {
          // Points in the right half-plane, away from the origin and the atan2 branch cut.
          const path = polarPoints.map(([r, th]) => [r * Math.cos(th), r * Math.sin(th)]);
          const { worst, segments } = worstActuatorError(
            machine([{ type: 'function', from: ['x', 'y'], to: ['r', 'theta'], fn: polar, tolerance }]),
            polar,
            path,
            [50, 0],
          );
          expect(worst).toBeLessThanOrEqual(tolerance);
          let moves = 0;
          path.reduce((from, p) => (Math.hypot(p[0] - from[0], p[1] - from[1]) > 1e-9 ? (moves++, p) : from), [50, 0]);
          expect(segments).toBeGreaterThanOrEqual(moves);
        },
      ),
      { numRuns: 60 },
    );
  });

  it('polar: judges a piece by the peak between its samples, not the samples alone', () => {
    // Found by dense checks (the property above at more runs): a θ bent hard near the pole,
    // which peaks between two samples, and a flat-topped θ across a wide arc, which peaks
    // beside the middle one. Judged by the samples at ¼, ½ and ¾ alone, a piece of each
    // passed the tolerance, by 1.3e-6 and 1.3e-4 of it.
    const polar = ([x, y]: readonly number[]) => [Math.hypot(x, y), Math.atan2(y, x) * 50];
    const cases = [
      [[5, 0.003979601923493768], [58.82319636173942, 0]],
      [[5, 1.197496446496894], [51.562737063180606, 0], [5, 0]],
    ];
    for (const polarPoints of cases) {
      const path = polarPoints.map(([r, th]) => [r * Math.cos(th), r * Math.sin(th)]);
      const cfg = machine([{ type: 'function', from: ['x', 'y'], to: ['r', 'theta'], fn: polar, tolerance: 0.05 }]);
      expect(worstActuatorError(cfg, polar, path, [50, 0]).worst).toBeLessThanOrEqual(0.05);
    }
  });

  it('subdivides no more than needed: a tighter tolerance gives more pieces', () => {
    const polar = ([x, y]: readonly number[]) => [Math.hypot(x, y), Math.atan2(y, x) * 50];
    const count = (tolerance: number) =>
      worstActuatorError(machine([{ type: 'function', from: ['x', 'y'], to: ['r', 't'], fn: polar, tolerance }]), polar, [[0.001, 80]], [80, 0]).segments;
    const coarse = count(0.1);
    const fine = count(0.001);
    expect(coarse).toBeGreaterThan(1);
    // Chord error shrinks with the square of the piece length: 100× tighter ≈ 10× more pieces.
    expect(fine / coarse).toBeGreaterThan(5);
    expect(fine / coarse).toBeLessThan(20);
  });

  it('keeps both cartesian and actuator tracks, with the cartesian path still straight', () => {
    const polar = ([x, y]: readonly number[]) => [Math.hypot(x, y), Math.atan2(y, x)];
    const maxl = createMAXL(machine([{ type: 'function', from: ['x', 'y'], to: ['r', 'theta'], fn: polar }]), { initialPosition: [10, 0] });
    queueOf(maxl).append({ endPosition: [10, 10] });
    queueOf(maxl).planToRest();
    const segs = [];
    for (let s = queueOf(maxl).transmitNext(0); s; s = queueOf(maxl).transmitNext(0)) segs.push(s);
    expect(segs.length).toBeGreaterThan(1);
    for (const s of segs) {
      expect(s.start[0]).toBeCloseTo(10, 12);
      expect(s.unit[0]).toBeCloseTo(0, 12);
    }
    expect(new Set(segs.map((s) => s.moveId)).size).toBe(1);
    // Speed is continuous through the pieces: no stops inside one move.
    for (let k = 1; k < segs.length; k++) expect(segs[k].entry2).toBeGreaterThan(0);
  });
});
