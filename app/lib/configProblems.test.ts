import { describe, expect, it } from 'vitest';
import { blotPlotter } from '../../core/sim/presets/blotPlotter.ts';
import { configProblems } from './configProblems.ts';
import type { MachineConfig } from '../worker/protocol.ts';

const valid = (): MachineConfig => blotPlotter().config as MachineConfig;

describe('configProblems', () => {
  it('a preset has none', () => {
    expect(configProblems(valid())).toEqual([]);
  });

  it('lists every bad field, not only the first', () => {
    const c = valid();
    c.limits = { ...c.limits, maxVelocity: -50, maxAcceleration: Number.NaN };
    c.softLimits = { x: [10, 5], y: [0, 125] };
    c.eventChannels = ['pen', 'pen'];
    const fields = configProblems(c).map((p) => p.field);
    expect(fields).toEqual(expect.arrayContaining(['limits.maxVelocity', 'limits.maxAcceleration', 'softLimits.x']));
    expect(fields.some((f) => f.startsWith('eventChannels'))).toBe(true);
    expect(new Set(fields).size).toBe(fields.length);
  });

  it('names a transform by its own place in the list', () => {
    const c = valid();
    c.transforms = [...(c.transforms ?? []), { type: 'corexy', from: ['x', 'nope'], to: ['c', 'd'] }];
    const problems = configProblems(c);
    expect(problems.some((p) => p.field.startsWith('transforms[1]'))).toBe(true);
    expect(problems.some((p) => p.field.startsWith('transforms[0]'))).toBe(false);
  });
});
