import { describe, expect, it } from 'vitest';
import { parseConfig } from './configStorage.ts';

describe('parseConfig (Configure → Import JSON)', () => {
  it('refuses a file that is not JSON, saying so and where the parser stopped', () => {
    expect(() => parseConfig('{"motionAxes": ["x", "y"],')).toThrow(/^The file is not JSON: /);
    expect(() => parseConfig('')).toThrow(/^The file is not JSON: /);
  });

  it.each([
    ['null', 'null'],
    ['a number', '42'],
    ['a list', '[1, 2]'],
    ['an object without motionAxes', '{"limits": {"maxVelocity": 100}}'],
    ['motionAxes that are not a list', '{"motionAxes": "xy", "limits": {}}'],
  ])('refuses %s as not a machine configuration', (_what, text) => {
    expect(() => parseConfig(text)).toThrow('The file is not a MAXL machine configuration: it needs at least "motionAxes" and "limits".');
  });

  it('returns a configuration to check, bad fields and all: Configure lists its problems before Apply', () => {
    const draft = parseConfig('{"motionAxes": ["x", "y"], "limits": {"maxVelocity": -5}}');
    expect(draft.limits.maxVelocity).toBe(-5);
  });
});
