import { describe, expect, it } from 'vitest';
import { createMAXL, MaxlError, type MaxlConfig, type SubscriptionConfig } from '../index.ts';
import { queueOf } from '../maxl.ts';

const good: MaxlConfig = {
  motionAxes: ['x', 'y'],
  eventChannels: ['powerOut'],
  limits: { maxVelocity: 250, maxAcceleration: 3000, junctionDeviation: 0.05 },
  transforms: [{ type: 'corexy', from: ['x', 'y'], to: ['a', 'b'] }],
  subscriptions: [
    { device: 'motorOne', track: 'a', reader: 'stepper' },
    { device: 'motorTwo', track: 'b', reader: 'stepper' },
    { device: 'laserModule', track: 'velocity', reader: 'velocityReader' },
    { device: 'laserModule', track: 'powerOut', reader: 'laserPower' },
  ],
};

function fieldOf(cfg: unknown): string | undefined {
  try {
    createMAXL(cfg as MaxlConfig);
  } catch (err) {
    expect(err).toBeInstanceOf(MaxlError);
    expect((err as MaxlError).code).toBe('CONFIG_INVALID');
    return (err as MaxlError).field;
  }
  throw new Error('config was accepted');
}

const edit = (patch: (c: MaxlConfig) => void): MaxlConfig => {
  const c = structuredClone({ ...good, transforms: undefined }) as MaxlConfig;
  c.transforms = [{ type: 'corexy', from: ['x', 'y'], to: ['a', 'b'] }];
  patch(c);
  return c;
};

describe('config validation', () => {
  it('accepts the paper-style config and lists its tracks', () => {
    const maxl = createMAXL(good);
    expect(maxl.config.tracks.map((t) => `${t.name}:${t.kind}`)).toEqual([
      'x:position', 'y:position', 'a:position', 'b:position', 'velocity:velocity', 'acceleration:acceleration', 'powerOut:event',
    ]);
    expect(maxl.config.limits.junctionDeviation).toBe(0.05);
  });

  it.each([
    ['an unknown field', (c: MaxlConfig) => ((c as unknown as Record<string, unknown>).motionAxis = ['x']), 'motionAxis'],
    ['no motion axes', (c: MaxlConfig) => (c.motionAxes = []), 'motionAxes'],
    ['a duplicate axis', (c: MaxlConfig) => (c.motionAxes = ['x', 'x']), 'motionAxes[1]'],
    ['an axis named like a channel', (c: MaxlConfig) => (c.eventChannels = ['y']), 'eventChannels[0]'],
    ['a reserved track name', (c: MaxlConfig) => (c.eventChannels = ['velocity']), 'eventChannels[0]'],
    ['a bad name', (c: MaxlConfig) => (c.motionAxes = ['x', 'two words']), 'motionAxes[1]'],
    ['zero velocity', (c: MaxlConfig) => (c.limits.maxVelocity = 0), 'limits.maxVelocity'],
    ['negative acceleration', (c: MaxlConfig) => (c.limits.maxAcceleration = -1), 'limits.maxAcceleration'],
    ['NaN junction deviation', (c: MaxlConfig) => (c.limits.junctionDeviation = NaN), 'limits.junctionDeviation'],
    ['a velocity too small to time (1e-300 squares to 0)', (c: MaxlConfig) => (c.limits.maxVelocity = 1e-300), 'limits.maxVelocity'],
    ['a velocity no reader can step (1e6 mm/s)', (c: MaxlConfig) => (c.limits.maxVelocity = 1e6), 'limits.maxVelocity'],
    ['an acceleration past the wire (4e38, infinite as f32)', (c: MaxlConfig) => (c.limits.maxAcceleration = 4e38), 'limits.maxAcceleration'],
    ['a per-axis acceleration too small (1e-300)', (c: MaxlConfig) => (c.limits.maxAcceleration = [3000, 1e-300]), 'limits.maxAcceleration[1]'],
    ['missing acceleration', (c: MaxlConfig) => delete c.limits.maxAcceleration, 'limits.maxAcceleration'],
    ['a per-axis array of the wrong length', (c: MaxlConfig) => (c.limits.axisMaxVelocity = [100]), 'limits.axisMaxVelocity'],
    ['a zero per-axis entry', (c: MaxlConfig) => (c.limits.maxAcceleration = [3000, 0]), 'limits.maxAcceleration[1]'],
    ['per-axis limits given twice', (c: MaxlConfig) => ((c.limits.maxVelocity = [1, 2]), (c.limits.axisMaxVelocity = [1, 2])), 'limits.axisMaxVelocity'],
    ['an unknown limit', (c: MaxlConfig) => ((c.limits as Record<string, unknown>).jerk = 5), 'limits.jerk'],
    ['a corexy with 3 inputs', (c: MaxlConfig) => (c.transforms = [{ type: 'corexy', from: ['x', 'y', 'x'], to: ['a', 'b'] }]), 'transforms[0].from'],
    ['a corexy with 1 output', (c: MaxlConfig) => (c.transforms = [{ type: 'corexy', from: ['x', 'y'], to: ['a'] }]), 'transforms[0].to'],
    ['a transform of an unknown axis', (c: MaxlConfig) => (c.transforms = [{ type: 'hbot', from: ['x', 'z'], to: ['a', 'b'] }]), 'transforms[0].from[1]'],
    ['a matrix with a missing row', (c: MaxlConfig) => (c.transforms = [{ type: 'linear', from: ['x'], to: ['a', 'b'], matrix: [[1]] }]), 'transforms[0].matrix'],
    ['a matrix row of the wrong width', (c: MaxlConfig) => (c.transforms = [{ type: 'linear', from: ['x', 'y'], to: ['a'], matrix: [[1]] }]), 'transforms[0].matrix[0]'],
    ['a function that is not one', (c: MaxlConfig) => (c.transforms = [{ type: 'function', from: ['x'], to: ['a'], fn: 3 as never }]), 'transforms[0].fn'],
    ['an unknown transform type', (c: MaxlConfig) => (c.transforms = [{ type: 'delta', from: ['x'], to: ['a'] } as never]), 'transforms[0].type'],
    ['an actuator named like an axis', (c: MaxlConfig) => (c.transforms = [{ type: 'corexy', from: ['x', 'y'], to: ['a', 'x'] }]), 'transforms[0].to[1]'],
    ['a subscription to an unknown track', (c: MaxlConfig) => (c.subscriptions![0].track = 'z'), 'subscriptions[0].track'],
    ['a subscription without a reader', (c: MaxlConfig) => delete (c.subscriptions![1] as Partial<SubscriptionConfig>).reader, 'subscriptions[1].reader'],
    ['a subscription that is not an object', (c: MaxlConfig) => (c.subscriptions![2] = 'laser' as never), 'subscriptions[2]'],
    ['a subscription with an extra field', (c: MaxlConfig) => ((c.subscriptions![0] as unknown as Record<string, string>).kind = 'stepper'), 'subscriptions[0].kind'],
    ['one reader bound twice', (c: MaxlConfig) => c.subscriptions!.push({ device: 'motorOne', track: 'b', reader: 'stepper' }), 'subscriptions[4].reader'],
    ['soft limits of an unknown axis', (c: MaxlConfig) => (c.softLimits = { z: [0, 1] }), 'softLimits.z'],
    ['inverted soft limits', (c: MaxlConfig) => (c.softLimits = { x: [10, 0] }), 'softLimits.x'],
    ['a fractional queue capacity', (c: MaxlConfig) => (c.queueCapacity = 2.5), 'queueCapacity'],
  ])('rejects %s, naming the field', (_what, patch, field) => {
    expect(fieldOf(edit(patch))).toBe(field);
  });

  it('accepts scalar and per-axis limits together, and applies both', () => {
    const maxl = createMAXL({ motionAxes: ['x', 'y'], limits: { maxVelocity: 100, axisMaxVelocity: [50, 200], maxAcceleration: [1000, 1000] } });
    expect(maxl.config.limits.maxSpeed).toBe(100);
    expect(maxl.config.limits.axisMaxSpeed).toEqual([50, 200]);
    expect(maxl.config.limits.maxAccel).toBe(Infinity);
    expect(maxl.config.limits.axisMaxAccel).toEqual([1000, 1000]);
    queueOf(maxl).append({ endPosition: [100, 0] }); // along x: capped at 50 by the axis limit
    queueOf(maxl).append({ endPosition: [100, 100] }); // along y: capped at 100 by the magnitude
    const [sx, sy] = queueOf(maxl).segments();
    expect(Math.sqrt(sx.cruise2)).toBe(50);
    expect(Math.sqrt(sy.cruise2)).toBe(100);
  });
});
