/**
 * The plot's moves and its time: the pen sequence per path, a file's own speeds
 * and holds, and the plot time equal to the planner's duration of those very
 * moves — planPath's, and the queue's own when it holds the whole job, with and
 * without a link's floor on segment durations.
 */
import { describe, expect, it } from 'vitest';
import { blotPlotter } from '../../../../core/sim/presets/index.ts';
import { createMAXL, isDwell, planPath, type Move } from '../../../../core/index.ts';
import type { PenSettings } from '../penSequence.ts';
import { importSvg } from './svgImport.ts';
import { arrange, DEFAULT_ARRANGEMENT } from './arrange.ts';
import { sortPaths } from './ordering.ts';
import { pathMoves, plotJobMoves, plotTime } from './plotJob.ts';
import type { PlotPath } from './paths.ts';
import { queueOf } from '../../../../core/maxl.ts';

const pen: PenSettings = { channel: 'pen', up: 0, down: 1, delayUp_s: 0.1, delayDown_s: 0.15, drawSpeed: 40, travelSpeed: 120, axes: ['x', 'y'] };
const blot = blotPlotter().config;

const drawing = importSvg(
  'test.svg',
  `<svg xmlns="http://www.w3.org/2000/svg" width="60mm" height="60mm" viewBox="0 0 60 60">
  <g transform="translate(30 30) rotate(15)"><circle r="12"/><path d="M-20 -20 C -10 -30 10 10 20 -20 A 8 8 0 0 1 20 0"/></g>
  <rect x="2" y="2" width="10" height="6" rx="2"/></svg>`,
);
const placed = arrange(drawing.paths, DEFAULT_ARRANGEMENT, { minX: 0, minY: 0, maxX: 125, maxY: 125 }, [0, 0]);
const start = [3, 4];
const paths = sortPaths(placed.paths, [3, 4]);

describe('plotJobMoves', () => {
  it('lifts the pen first, then per path: travel, pen down, the points, pen up', () => {
    const p: PlotPath = { points: Float64Array.from([1, 1, 2, 1, 2, 2]), speeds: null, dwells: null };
    expect(plotJobMoves([p], pen)).toEqual([
      { dwell_s: 0.1, eventChannels: { pen: 0 } },
      { endPosition: { x: 1, y: 1 }, maxVelocity: 120 },
      { dwell_s: 0.15, eventChannels: { pen: 1 } },
      { endPosition: { x: 2, y: 1 }, maxVelocity: 40 },
      { endPosition: { x: 2, y: 2 }, maxVelocity: 40 },
      { dwell_s: 0.1, eventChannels: { pen: 0 } },
    ]);
  });

  it('a file’s own segment speeds and holds (G-code F and G4) go with their segments and points', () => {
    const p: PlotPath = { points: Float64Array.from([0, 0, 1, 0, 2, 0]), speeds: Float64Array.from([10, 0]), dwells: Float64Array.from([0.5, 0, 2500]) };
    const moves = plotJobMoves([p], pen);
    expect(moves.slice(2)).toEqual([
      { dwell_s: 0.15, eventChannels: { pen: 1 } },
      { dwell_s: 0.5 },
      { endPosition: { x: 1, y: 0 }, maxVelocity: 10 },
      { endPosition: { x: 2, y: 0 }, maxVelocity: 40 },
      // 2 500 s is longer than one dwell may be: two of them.
      { dwell_s: 2000 },
      { dwell_s: 500 },
      { dwell_s: 0.1, eventChannels: { pen: 0 } },
    ]);
  });
});

describe('the plot time', () => {
  const moves = plotJobMoves(paths, pen);

  /** The queue's own plan of the whole job: every move appended, planned to rest, durations summed. */
  function queueDuration(jobMoves: readonly Move[], floor_s: number): number {
    const maxl = createMAXL({ ...blot, queueCapacity: jobMoves.length + 10 }, { initialPosition: start });
    queueOf(maxl).setMinSegmentDuration(floor_s);
    for (const m of jobMoves) queueOf(maxl).append(m);
    queueOf(maxl).planToRest();
    return queueOf(maxl).segments().reduce((t, s) => t + s.duration_s, 0);
  }

  it('is planPath’s duration of the job’s moves, dwells included', () => {
    const t = plotTime(moves, blot.motionAxes, start, blot.limits, 0);
    const hand: Parameters<typeof planPath>[1] = [];
    let at = [...start];
    for (const m of moves) {
      if (isDwell(m)) hand.push({ dwell_s: m.dwell_s });
      else {
        const e = m.endPosition as Record<string, number>;
        at = [e.x ?? at[0], e.y ?? at[1]];
        hand.push({ end: at, maxVelocity: m.maxVelocity });
      }
    }
    expect(t).toBe(planPath(start, hand, blot.limits).duration);
    const dwells = moves.filter(isDwell).reduce((s, m) => s + (isDwell(m) ? m.dwell_s : 0), 0);
    expect(t).toBeGreaterThan(dwells + 1);
  });

  it('equals the queue’s own plan of the job, with and without a link’s floor on segment durations', () => {
    for (const floor_us of [0, 4000, 50_000]) {
      const t = plotTime(moves, blot.motionAxes, start, blot.limits, floor_us);
      expect(Math.abs(t - queueDuration(moves, floor_us * 1e-6))).toBeLessThan(1e-9 * t);
    }
    // A 50 ms floor caps the ~1.4 mm chords below the 40 mm/s pen-down speed.
    expect(plotTime(moves, blot.motionAxes, start, blot.limits, 50_000)).toBeGreaterThan(plotTime(moves, blot.motionAxes, start, blot.limits, 0) * 1.05);
  });

  it('pathMoves makes positions whole from the start and names a wrong axis', () => {
    expect(pathMoves([{ endPosition: { y: 5 } }, { dwell_s: 1 }, { endPosition: { x: 2 }, maxVelocity: 3 }], ['x', 'y'], [1, 1])).toEqual([{ end: [1, 5] }, { dwell_s: 1 }, { end: [2, 5], maxVelocity: 3 }]);
    expect(() => pathMoves([{ endPosition: { z: 5 } }], ['x', 'y'], [0, 0])).toThrow(/"z" is not a motion axis/);
  });
});
