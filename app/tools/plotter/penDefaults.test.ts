import { describe, expect, it } from 'vitest';
import { blotPlotter } from '../../../core/sim/presets/blotPlotter.ts';
import { penChannel, penDefaults, penSettingsProblem } from './penDefaults.ts';

const blot = { motionAxes: ['x', 'y'], eventChannels: ['pen'], limits: { maxVelocity: 120 } };

describe('pen defaults', () => {
  it('on the simulated Blot: channel pen, 0 up, 1 down, delays a little longer than its servo swings', () => {
    const pen = penDefaults(blot, 'blotPlotter')!;
    expect(pen).toMatchObject({ channel: 'pen', up: 0, down: 1, drawSpeed: 120, travelSpeed: 120, axes: ['x', 'y'] });
    const servo = blotPlotter().plant.pen!;
    // Each delay covers the swing and a 20 ms servo frame.
    expect(pen.delayDown_s * 1e6).toBeGreaterThanOrEqual(servo.dropDelay_us + 20_000);
    expect(pen.delayUp_s * 1e6).toBeGreaterThanOrEqual(servo.liftDelay_us + 20_000);
    expect(pen.delayDown_s).toBeLessThanOrEqual(0.2);
  });

  it('on real boards: the "pen" channel or the first one, and safe delays', () => {
    expect(penChannel({ ...blot, eventChannels: ['laser', 'pen'] })).toBe('pen');
    expect(penChannel({ ...blot, eventChannels: ['servo'] })).toBe('servo');
    const pen = penDefaults({ ...blot, eventChannels: ['servo'] }, null)!;
    expect(pen.channel).toBe('servo');
    expect(pen.delayDown_s).toBe(0.25);
    expect(pen.delayUp_s).toBe(0.25);
    expect(penDefaults({ ...blot, eventChannels: [] }, null)).toBeNull();
  });

  it('edited settings: what is wrong, in words', () => {
    const pen = penDefaults(blot, 'blotPlotter')!;
    expect(penSettingsProblem(pen, blot)).toBeNull();
    expect(penSettingsProblem({ ...pen, channel: 'laser' }, blot)).toMatch(/"laser" is not an event channel of this machine \(pen\)/);
    expect(penSettingsProblem({ ...pen, delayUp_s: -0.1 }, blot)).toMatch(/pen-up delay must be between 0 and 10 s/);
    expect(penSettingsProblem({ ...pen, drawSpeed: 0 }, blot)).toMatch(/draw speed must be above 0/);
    expect(penSettingsProblem({ ...pen, down: NaN }, blot)).toMatch(/pen down value must be a number/);
    expect(penSettingsProblem({ ...pen, axes: ['x', 'x'] }, blot)).toMatch(/two different motion axes/);
  });
});
