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
    ['an object without limits', '{"motionAxes": ["x", "y"]}'],
  ])('refuses %s as not a machine configuration', (_what, text) => {
    expect(() => parseConfig(text)).toThrow('The file is not a MAXL machine configuration: it needs at least "motionAxes" and "limits".');
  });

  // Parts of a kind the editor cannot show (it would fail to draw them): refused, naming the part.
  it.each([
    ['{"motionAxes": "xy", "limits": {}}', '"motionAxes" must be a list of axis names'],
    ['{"motionAxes": ["x", 2], "limits": {}}', '"motionAxes" must be a list of axis names'],
    ['{"motionAxes": ["x"], "limits": null}', '"limits" must be an object'],
    ['{"motionAxes": ["x"], "limits": [100]}', '"limits" must be an object'],
    ['{"motionAxes": ["x"], "limits": {}, "eventChannels": "pen"}', '"eventChannels" must be a list of channel names'],
    ['{"motionAxes": ["x"], "limits": {}, "subscriptions": "none"}', '"subscriptions" must be a list'],
    ['{"motionAxes": ["x"], "limits": {}, "subscriptions": [{"device": "a", "reader": "b", "track": "x"}, 3]}', '"subscriptions[1]" must be an object'],
    ['{"motionAxes": ["x"], "limits": {}, "transforms": {"type": "corexy"}}', '"transforms" must be a list'],
    ['{"motionAxes": ["x", "y"], "limits": {}, "transforms": [{"type": "corexy"}]}', '"transforms[0].from" must be a list of motion axis names'],
    ['{"motionAxes": ["x", "y"], "limits": {}, "transforms": [{"type": "corexy", "from": ["x", "y"], "to": "ab"}]}', '"transforms[0].to" must be a list of actuator axis names'],
    ['{"motionAxes": ["x"], "limits": {}, "softLimits": [0, 100]}', '"softLimits" must be an object'],
    ['{"motionAxes": ["x"], "limits": {}, "softLimits": {"x": 100}}', '"softLimits.x" must be [min, max]'],
  ])('refuses %s: %s, importing nothing', (text, words) => {
    expect(() => parseConfig(text)).toThrow(`The file is not a MAXL machine configuration: ${words}`);
    expect(() => parseConfig(text)).toThrow(/Nothing was imported\.$/);
  });

  it('returns a configuration to check, bad fields and all: Configure lists its problems before Apply', () => {
    const draft = parseConfig('{"motionAxes": ["x", "y"], "limits": {"maxVelocity": -5}}');
    expect(draft.limits.maxVelocity).toBe(-5);
  });
});
