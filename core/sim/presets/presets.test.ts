import { describe, expect, it } from 'vitest';
import { resolveConfig } from '../../config/validate.ts';
import { Plant } from '../plant/plant.ts';
import { PRESETS } from './index.ts';

const TRACK_READER = { position: 'position', velocity: 'velocity', acceleration: 'acceleration', event: 'event' } as const;

describe.each(Object.entries(PRESETS))('preset %s', (id, make) => {
  const preset = make();

  it('has a MAXL config the core accepts', () => {
    expect(preset.id).toBe(id);
    expect(() => resolveConfig(preset.config)).not.toThrow();
  });

  it('subscribes only readers its devices declare, with the kind the track needs', () => {
    const resolved = resolveConfig(preset.config);
    for (const sub of resolved.subscriptions) {
      const device = preset.devices.find((d) => d.name === sub.device);
      expect(device, `device ${sub.device}`).toBeDefined();
      const reader = device?.readers.find((r) => r.name === sub.reader);
      expect(reader, `${sub.device}/${sub.reader}`).toBeDefined();
      const track = resolved.tracks.find((t) => t.name === sub.track);
      expect(track, `track ${sub.track}`).toBeDefined();
      expect(reader?.kind).toBe(TRACK_READER[track!.kind]);
    }
    // Every device reads something, or writes samples.
    for (const d of preset.devices) {
      const used = resolved.subscriptions.some((s) => s.device === d.name) || d.readers.some((r) => r.kind === 'sensor');
      expect(used, d.name).toBe(true);
    }
  });

  it('wires its plant to devices it has, and builds', () => {
    const names = new Set(preset.devices.map((d) => d.name));
    for (const m of preset.plant.motors) expect(names.has(m.device), m.device).toBe(true);
    for (const part of [preset.plant.accelerometer, preset.plant.ledStrip, preset.plant.pen]) if (part) expect(names.has(part.device)).toBe(true);
    const plant = new Plant(preset.plant, { seed: 1 });
    // Motors are the actuator axes the config's transform produces (or the motion axes directly).
    const resolved = resolveConfig(preset.config);
    const driven = resolved.actuatorAxes.length > 0 ? resolved.actuatorAxes : resolved.motionAxes;
    expect(Object.keys(plant.motors).sort()).toEqual([...driven].sort());
    expect(plant.axisNames).toEqual(resolved.motionAxes);
  });
});
