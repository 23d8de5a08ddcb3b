/**
 * Moves the author must refuse before anything is queued: a function transform
 * that gives NaN or throws, and a position (or a CoreXY actuator sum) beyond what
 * the wire can carry. Each refusal is a rejected promise with a MaxlError, never a
 * synchronous throw, and the queue is left as it was.
 */
import { describe, expect, it } from 'vitest';
import { createMAXL, type Maxl } from '../maxl.ts';
import { MaxlError } from '../errors.ts';
import type { MaxlConfig } from '../config/types.ts';

const limits = { maxVelocity: 100, maxAcceleration: 1000 };

function withTransform(fn: (p: readonly number[]) => number[], linear: boolean): Maxl {
  const config: MaxlConfig = { motionAxes: ['x', 'y'], limits, transforms: [{ type: 'function', from: ['x', 'y'], to: ['a'], fn, linear }] };
  return createMAXL(config);
}

async function refused(maxl: Maxl, move: Parameters<Maxl['addSegmentToQueue']>[0]): Promise<MaxlError> {
  let result: Promise<unknown>;
  try {
    result = maxl.addSegmentToQueue(move);
  } catch (err) {
    throw new Error(`addSegmentToQueue threw synchronously: ${String(err)}`);
  }
  const err = await result.then(
    () => null,
    (e: unknown) => e,
  );
  expect(err).toBeInstanceOf(MaxlError);
  expect(maxl.queue.untransmittedCount).toBe(0);
  return err as MaxlError;
}

describe('moves refused before they are queued', () => {
  for (const linear of [true, false]) {
    it(`a function transform that gives NaN (${linear ? 'declared linear' : 'nonlinear'})`, async () => {
      const maxl = withTransform((p) => [p[0] > 20 ? Number.NaN : p[0] + p[1]], linear);
      const err = await refused(maxl, { endPosition: [40, 20] });
      expect(err.code).toBe('MOVE_INVALID');
      expect(err.field).toBe('transforms[0].fn');
      expect(err.message).toContain('NaN');
    });
  }

  it('a nonlinear transform that gives NaN only inside the move is refused, not subdivided forever', async () => {
    const maxl = withTransform((p) => [Math.abs(p[0] - 10) < 1 ? Number.NaN : p[0]], false);
    const err = await refused(maxl, { endPosition: [20, 0] });
    expect(err.message).toContain('NaN');
  });

  it('a function transform that throws', async () => {
    const maxl = withTransform(() => {
      throw new Error('out of reach');
    }, false);
    const err = await refused(maxl, { endPosition: [1, 1] });
    expect(err.message).toContain('out of reach');
  });

  it('a position beyond the wire range, and a CoreXY sum beyond it inside valid soft limits', async () => {
    const plain = createMAXL({ motionAxes: ['x'], limits });
    expect((await refused(plain, { endPosition: [40_000] })).field).toBe('endPosition.x');
    const corexy = createMAXL({ motionAxes: ['x', 'y'], limits, transforms: [{ type: 'corexy', from: ['x', 'y'], to: ['a', 'b'] }] });
    const err = await refused(corexy, { endPosition: [20_000, 20_000] });
    expect(err.message).toMatch(/actuator a would be at 40000 mm/);
    // Just inside the range is fine.
    await expect(corexy.addSegmentToQueue({ endPosition: [16_000, 16_000] })).resolves.toMatchObject({ skipped: false });
  });

  it('an event value or a per-move acceleration the wire cannot carry', async () => {
    const maxl = createMAXL({ motionAxes: ['x', 'y'], eventChannels: ['laser'], limits });
    // Finite as a double, infinite as the wire's 32-bit float.
    const big = await refused(maxl, { endPosition: [1, 1], eventChannels: { laser: -3.5e38 } });
    expect(big.field).toBe('eventChannels.laser');
    expect(big.message).toMatch(/within ±3\.4e38/);
    const gentle = await refused(maxl, { endPosition: [1, 1], maxAcceleration: 5e-324 });
    expect(gentle.field).toBe('maxAcceleration');
    expect(gentle.message).toMatch(/at least 0\.001 mm\/s²/);
  });


  it('a nonlinear transform with a tolerance too fine, or a move it would cut into too many pieces', async () => {
    const config = (tolerance: number): MaxlConfig => ({
      motionAxes: ['x', 'y'],
      limits,
      transforms: [{ type: 'function', from: ['x', 'y'], to: ['a'], fn: (p) => [10 * Math.sin(p[0] * 1000)], tolerance }],
    });
    expect(() => createMAXL(config(5e-324))).toThrow(expect.objectContaining({ code: 'CONFIG_INVALID', field: 'transforms[0].tolerance' }));
    // Ripples of 6 µm period over 60 mm: far more than 10 000 pieces at 0.1 µm.
    const err = await refused(createMAXL(config(1e-4)), { endPosition: [60, 0] });
    expect(err.code).toBe('MOVE_INVALID');
    expect(err.message).toMatch(/needs more than 10000 pieces to follow this move within its tolerance/);
  });
});
