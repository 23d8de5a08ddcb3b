import { describe, expect, it } from 'vitest';
import { planPath } from './planPath.ts';
import { MaxlError } from '../errors.ts';
import { createMAXL } from '../maxl.ts';

const limits = { maxVelocity: 100, maxAcceleration: 1000 };

describe('planPath refuses bad input in its own words', () => {
  it('names the key a path move has: end, not endPosition', () => {
    let caught: unknown;
    try {
      planPath([0, 0], [{ end: [1, 0] }, { end: [1, Number.NaN] }], limits);
    } catch (err) {
      caught = err;
    }
    expect(caught).toBeInstanceOf(MaxlError);
    expect((caught as MaxlError).field).toBe('moves[1].end[1]');
    expect((caught as MaxlError).message).not.toContain('endPosition');
  });

  it('a time that is not a number is refused, not read as the start', () => {
    const plan = planPath([0, 0], [{ end: [10, 0] }], limits);
    expect(() => plan.sample(Number.NaN)).toThrow(expect.objectContaining({ code: 'MOVE_INVALID', field: 't' }));
    expect(plan.sample(plan.duration).position[0]).toBeCloseTo(10, 12);
  });

  it('a speed cap too small to time is refused (1e-300 would square to 0)', async () => {
    expect(() => planPath([0, 0], [{ end: [1, 0], maxVelocity: 1e-300 }], limits)).toThrow(expect.objectContaining({ code: 'MOVE_INVALID', field: 'moves[0].maxVelocity' }));
    const maxl = createMAXL({ motionAxes: ['x'], limits });
    await expect(maxl.addSegmentToQueue({ endPosition: [1], maxVelocity: 1e-300 })).rejects.toMatchObject({ code: 'MOVE_INVALID', field: 'maxVelocity' });
    expect(maxl.queue.untransmittedCount).toBe(0);
  });
});
