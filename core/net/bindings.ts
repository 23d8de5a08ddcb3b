/**
 * Binding the configured subscriptions to the readers the devices report in their
 * HELLO: which reader of which device reads which track, in which slot. Every
 * mismatch is collected, so that one error lists them all: a device that is not
 * connected, a reader a device does not have, a reader of the wrong kind for its
 * track.
 */
import type { ResolvedConfig, TrackKind } from '../config/types.ts';
import type { MessageOf } from './messages.ts';
import { ReaderKind, type ReaderKindName } from './protocol.ts';
import type { PositionSlot } from './segmentEncoding.ts';
import type { DeviceInfo } from './session.ts';

export interface DevicePlan {
  device: string;
  /** SUBSCRIBE messages to send, in order */
  subscribe: MessageOf<'SUBSCRIBE'>[];
  positionSlots: PositionSlot[];
  /** event channel index → event slot */
  eventSlots: Map<number, number>;
  /** whether the device reads the trajectory at all (and so gets segments) */
  readsTrajectory: boolean;
}

export interface Mismatch {
  subscription: number;
  device: string;
  reader: string;
  track: string;
  problem: 'unknown device' | 'unknown reader' | 'wrong kind';
  message: string;
}

const READER_FOR_TRACK: Record<TrackKind, ReaderKindName> = {
  position: 'position',
  velocity: 'velocity',
  acceleration: 'acceleration',
  event: 'event',
};

export function bindSubscriptions(config: ResolvedConfig, devices: DeviceInfo[]): { plans: DevicePlan[]; mismatches: Mismatch[] } {
  const byName = new Map(devices.map((d) => [d.name, d]));
  const plans = new Map<string, DevicePlan>();
  const mismatches: Mismatch[] = [];
  const planFor = (device: string): DevicePlan => {
    let plan = plans.get(device);
    if (!plan) {
      plan = { device, subscribe: [], positionSlots: [], eventSlots: new Map(), readsTrajectory: false };
      plans.set(device, plan);
    }
    return plan;
  };
  const positionSlotOf = new Map<string, number>(); // `${device}/${track}` → slot

  config.subscriptions.forEach((sub, i) => {
    const base = { subscription: i, device: sub.device, reader: sub.reader, track: sub.track };
    const info = byName.get(sub.device);
    if (!info) {
      const connected = devices.map((d) => d.name).join(', ') || 'none';
      mismatches.push({ ...base, problem: 'unknown device', message: `subscriptions[${i}]: device "${sub.device}" is not connected (connected: ${connected})` });
      return;
    }
    const reader = info.readers.find((r) => r.name === sub.reader);
    if (!reader) {
      const readers = info.readers.map((r) => `${r.name} (${r.kind})`).join(', ') || 'none';
      mismatches.push({ ...base, problem: 'unknown reader', message: `subscriptions[${i}]: device "${sub.device}" has no reader "${sub.reader}" (its readers: ${readers})` });
      return;
    }
    const track = config.tracks.find((t) => t.name === sub.track);
    if (!track) return; // config validation already refused unknown tracks
    const wanted = READER_FOR_TRACK[track.kind];
    if (reader.kind !== wanted) {
      mismatches.push({
        ...base,
        problem: 'wrong kind',
        message: `subscriptions[${i}]: "${sub.device}"/"${sub.reader}" is ${withArticle(reader.kind)} reader, but track "${sub.track}" is ${withArticle(track.kind)} track: it needs ${withArticle(wanted)} reader`,
      });
      return;
    }
    const plan = planFor(sub.device);
    plan.readsTrajectory = true;
    let slot = 0;
    if (track.kind === 'position') {
      const key = `${sub.device}/${sub.track}`;
      if (!positionSlotOf.has(key)) {
        positionSlotOf.set(key, plan.positionSlots.length);
        const m = config.motionAxes.indexOf(sub.track);
        plan.positionSlots.push(m >= 0 ? { space: 'motion', index: m } : { space: 'actuator', index: config.actuatorAxes.indexOf(sub.track) });
      }
      slot = positionSlotOf.get(key) as number;
    } else if (track.kind === 'event') {
      const channel = config.eventChannels.indexOf(sub.track);
      if (!plan.eventSlots.has(channel)) plan.eventSlots.set(channel, plan.eventSlots.size);
      slot = plan.eventSlots.get(channel) as number;
    }
    plan.subscribe.push({ type: 'SUBSCRIBE', reader: reader.index, kind: ReaderKind[reader.kind], slot });
  });

  // Sensor readers need no track: they are switched on wherever they are.
  for (const info of devices) {
    for (const r of info.readers) {
      if (r.kind === 'sensor') planFor(info.name).subscribe.push({ type: 'SUBSCRIBE', reader: r.index, kind: ReaderKind.sensor, slot: 0 });
    }
  }
  return { plans: [...plans.values()], mismatches };
}

/** "an event", "a position": the indefinite article for a kind's name. */
function withArticle(word: string): string {
  return `${/^[aeiou]/i.test(word) ? 'an' : 'a'} ${word}`;
}
