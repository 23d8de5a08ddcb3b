import { describe, expect, it } from 'vitest';
import { isDwell } from '../../../core/index.ts';
import { plotMoves, strokeMoves, type PenSettings } from './penSequence.ts';

const pen: PenSettings = { channel: 'pen', up: 0, down: 1, delayUp_s: 0.12, delayDown_s: 0.15, drawSpeed: 40, travelSpeed: 100, axes: ['x', 'y'] };

describe('pen sequence', () => {
  it('a stroke is travel, pen down and wait, the points, pen up and wait', () => {
    const moves = strokeMoves([[10, 10], [20, 10], [20, 30]], pen);
    expect(moves).toEqual([
      { endPosition: { x: 10, y: 10 }, maxVelocity: 100 },
      { dwell_s: 0.15, eventChannels: { pen: 1 } },
      { endPosition: { x: 20, y: 10 }, maxVelocity: 40 },
      { endPosition: { x: 20, y: 30 }, maxVelocity: 40 },
      { dwell_s: 0.12, eventChannels: { pen: 0 } },
    ]);
  });

  it('a drawing lifts the pen first, and every pen-down has its pen-up', () => {
    const moves = plotMoves([[[0, 0], [1, 0]], [[5, 5], [6, 6], [7, 5]]], pen);
    expect(moves[0]).toEqual({ dwell_s: 0.12, eventChannels: { pen: 0 } });
    const penValues = moves.filter(isDwell).map((m) => (m.eventChannels as Record<string, number>).pen);
    expect(penValues).toEqual([0, 1, 0, 1, 0]);
    // No linear move at the drawing speed happens with the pen up.
    let down = false;
    for (const m of moves) {
      if (isDwell(m)) down = (m.eventChannels as Record<string, number>).pen === 1;
      else expect(m.maxVelocity).toBe(down ? 40 : 100);
    }
  });

  it('an empty stroke adds nothing', () => {
    expect(strokeMoves([], pen)).toEqual([]);
  });
});
