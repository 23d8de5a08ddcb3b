/**
 * Checks a MaxlConfig and resolves it. Every problem raises a MaxlError with code
 * CONFIG_INVALID whose `field` names the offending field, e.g.
 * `subscriptions[2].track`.
 */
import { configError } from '../errors.ts';
import { resolveLimits } from './limits.ts';
import type { MaxlConfig, ResolvedConfig, SubscriptionConfig, TrackInfo } from './types.ts';
import { resolveTransforms } from './transforms.ts';

/** Segments not yet transmitted that the queue holds before addSegmentToQueue waits, unless the config says otherwise. */
export const DEFAULT_QUEUE_CAPACITY = 512;

/** Track names readers may subscribe to besides axes and channels. */
export const PATH_TRACKS = ['velocity', 'acceleration'] as const;

/** Names travel on the wire and through the UI: short, plain identifiers. */
const NAME = /^[A-Za-z_][A-Za-z0-9_.-]{0,31}$/;

function checkName(field: string, name: unknown): string {
  if (typeof name !== 'string' || !NAME.test(name)) {
    throw configError(field, `${JSON.stringify(name)} is not a valid name (a letter or _, then up to 31 letters, digits, _ . -)`);
  }
  return name;
}

function nameList(field: string, value: unknown, required: boolean): string[] {
  if (value === undefined && !required) return [];
  if (!Array.isArray(value)) throw configError(field, 'must be an array of names');
  if (required && value.length === 0) throw configError(field, 'must name at least one axis');
  return value.map((n, i) => checkName(`${field}[${i}]`, n));
}

const KNOWN_FIELDS = ['motionAxes', 'eventChannels', 'limits', 'transforms', 'subscriptions', 'softLimits', 'queueCapacity'];

export function resolveConfig(config: MaxlConfig): ResolvedConfig {
  if (config === null || typeof config !== 'object') throw configError('config', 'must be an object');
  for (const key of Object.keys(config)) {
    if (!KNOWN_FIELDS.includes(key)) throw configError(key, `is not a known config field (known: ${KNOWN_FIELDS.join(', ')})`);
  }
  const motionAxes = nameList('motionAxes', config.motionAxes, true);
  const eventChannels = nameList('eventChannels', config.eventChannels, false);

  // Every track name must be unique across axes, actuators, channels and path tracks.
  const owner = new Map<string, string>();
  const claim = (name: string, field: string) => {
    const previous = owner.get(name);
    if (previous !== undefined) throw configError(field, `"${name}" is already used by ${previous}`);
    owner.set(name, field);
  };
  for (const name of PATH_TRACKS) owner.set(name, `the built-in ${name} track`);
  motionAxes.forEach((name, i) => claim(name, `motionAxes[${i}]`));
  eventChannels.forEach((name, i) => claim(name, `eventChannels[${i}]`));

  const limits = resolveLimits(config.limits, motionAxes.length);
  const transforms = resolveTransforms(config.transforms, motionAxes);
  const actuatorAxes: string[] = [];
  transforms.forEach((t, n) =>
    t.outputs.forEach((name, i) => {
      const field = `transforms[${n}].to[${i}]`;
      claim(checkName(field, name), field);
      actuatorAxes.push(name);
    }),
  );

  const tracks: TrackInfo[] = [
    ...motionAxes.map((name): TrackInfo => ({ name, kind: 'position', space: 'motion' })),
    ...actuatorAxes.map((name): TrackInfo => ({ name, kind: 'position', space: 'actuator' })),
    ...PATH_TRACKS.map((name): TrackInfo => ({ name, kind: name })),
    ...eventChannels.map((name): TrackInfo => ({ name, kind: 'event' })),
  ];

  const subscriptions = resolveSubscriptions(config.subscriptions, new Set(tracks.map((t) => t.name)));

  const softMin = new Array<number>(motionAxes.length).fill(-Infinity);
  const softMax = new Array<number>(motionAxes.length).fill(Infinity);
  if (config.softLimits !== undefined) {
    if (config.softLimits === null || typeof config.softLimits !== 'object') {
      throw configError('softLimits', 'must be an object of [min, max] per motion axis');
    }
    for (const [axis, range] of Object.entries(config.softLimits)) {
      const field = `softLimits.${axis}`;
      const i = motionAxes.indexOf(axis);
      if (i < 0) throw configError(field, `"${axis}" is not a motion axis (${motionAxes.join(', ')})`);
      if (!Array.isArray(range) || range.length !== 2 || !range.every((v) => typeof v === 'number' && !Number.isNaN(v))) {
        throw configError(field, 'must be [min, max] in mm');
      }
      if (!(range[0] < range[1])) throw configError(field, `min (${range[0]}) must be below max (${range[1]})`);
      softMin[i] = range[0];
      softMax[i] = range[1];
    }
  }

  let queueCapacity = DEFAULT_QUEUE_CAPACITY;
  if (config.queueCapacity !== undefined) {
    if (!Number.isInteger(config.queueCapacity) || config.queueCapacity < 1) {
      throw configError('queueCapacity', `must be a positive integer, got ${String(config.queueCapacity)}`);
    }
    queueCapacity = config.queueCapacity;
  }
  return { motionAxes, eventChannels, actuatorAxes, tracks, limits, transforms, subscriptions, softMin, softMax, queueCapacity };
}

function resolveSubscriptions(value: unknown, trackNames: Set<string>): SubscriptionConfig[] {
  if (value === undefined) return [];
  if (!Array.isArray(value)) throw configError('subscriptions', 'must be an array of { device, track, reader }');
  const bound = new Map<string, number>();
  return value.map((sub, i) => {
    const field = `subscriptions[${i}]`;
    if (sub === null || typeof sub !== 'object' || Array.isArray(sub)) throw configError(field, 'must be an object { device, track, reader }');
    for (const key of Object.keys(sub)) {
      if (!['device', 'track', 'reader'].includes(key)) throw configError(`${field}.${key}`, 'is not a subscription field (device, track, reader)');
    }
    const s = sub as Record<string, unknown>;
    for (const key of ['device', 'track', 'reader']) {
      if (typeof s[key] !== 'string' || (s[key] as string).length === 0) throw configError(`${field}.${key}`, 'must be a non-empty string');
    }
    const device = checkName(`${field}.device`, s.device);
    const reader = checkName(`${field}.reader`, s.reader);
    const track = s.track as string;
    if (!trackNames.has(track)) {
      throw configError(`${field}.track`, `"${track}" is not a track (tracks: ${[...trackNames].join(', ')})`);
    }
    const key = `${device}\u0000${reader}`;
    const earlier = bound.get(key);
    if (earlier !== undefined) {
      throw configError(`${field}.reader`, `reader "${reader}" of device "${device}" is already bound by subscriptions[${earlier}]`);
    }
    bound.set(key, i);
    return { device, track, reader };
  });
}
