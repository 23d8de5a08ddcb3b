import { describe, expect, it } from 'vitest';
import { clipSegment, StrokeClipper, type ClipStep } from './softLimitClip.ts';
import type { Point } from './thinning.ts';

const MIN = [0, 0];
const MAX = [125, 125];

function run(points: Point[]): { steps: ClipStep[]; clipper: StrokeClipper } {
  const clipper = new StrokeClipper(MIN, MAX);
  const steps = points.flatMap((p) => clipper.push(p));
  steps.push(...clipper.finish());
  return { steps, clipper };
}

describe('soft-limit clipping of a live stroke', () => {
  it('clips a segment to the box (Liang–Barsky)', () => {
    expect(clipSegment([-10, 50], [10, 50], MIN, MAX)).toEqual([0.5, 1]);
    expect(clipSegment([10, 10], [20, 20], MIN, MAX)).toEqual([0, 1]);
    expect(clipSegment([-10, -10], [-5, 200], MIN, MAX)).toBeNull();
    expect(clipSegment([-10, 62.5], [135, 62.5], MIN, MAX)).toEqual([10 / 145, 135 / 145]);
  });

  it('a stroke wholly inside is one piece, unchanged', () => {
    const { steps, clipper } = run([[10, 10], [20, 10], [20, 20]]);
    expect(steps).toEqual([{ type: 'start', p: [10, 10] }, { type: 'to', p: [20, 10] }, { type: 'to', p: [20, 20] }, { type: 'end' }]);
    expect(clipper.refused_mm).toBe(0);
    expect(clipper.firstRefused).toBeNull();
  });

  it('a stroke that leaves and comes back: the piece ends on the edge, the outside part is refused, a new piece starts on the edge', () => {
    const { steps, clipper } = run([[100, 50], [120, 50], [140, 50], [140, 60], [120, 60], [110, 60]]);
    expect(steps).toEqual([
      { type: 'start', p: [100, 50] },
      { type: 'to', p: [120, 50] },
      { type: 'to', p: [125, 50] },
      { type: 'end' },
      { type: 'start', p: [125, 60] },
      { type: 'to', p: [120, 60] },
      { type: 'to', p: [110, 60] },
      { type: 'end' },
    ]);
    expect(clipper.refused_mm).toBeCloseTo(15 + 10 + 15, 9);
    expect(clipper.firstRefused).toEqual([140, 50]);
  });

  it('a stroke that starts outside starts on the edge; one wholly outside draws nothing', () => {
    expect(run([[-20, 10], [20, 10]]).steps).toEqual([{ type: 'start', p: [0, 10] }, { type: 'to', p: [20, 10] }, { type: 'end' }]);
    const out = run([[-20, 10], [-10, 10], [-10, 200]]);
    expect(out.steps).toEqual([]);
    expect(out.clipper.refused_mm).toBeCloseTo(200, 9);
  });

  it('a stroke crossing the whole box in one segment draws the part inside', () => {
    expect(run([[-10, 62.5], [135, 62.5]]).steps).toEqual([{ type: 'start', p: [0, 62.5] }, { type: 'to', p: [125, 62.5] }, { type: 'end' }]);
  });

  it('grazing a corner from outside draws nothing', () => {
    expect(run([[-5, 5], [5, -5]]).steps).toEqual([]);
  });
});
