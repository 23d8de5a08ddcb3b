/**
 * Where the subscription editor draws things: devices with their readers on the
 * left, tracks on the right, one row each, and each subscription as a connection
 * between a reader row and a track row. Devices a subscription names that are not
 * connected get a ghost row, so that the broken connection can still be drawn and
 * explained.
 */
import type { ConfigCheck, DeviceView, SubscriptionProblem } from '../worker/protocol.ts';
import type { SubscriptionConfig } from '../../core/index.ts';

export const ROW_H = 30;
export const HEAD_H = 26;
export const GAP = 10;

export type LeftRow =
  | { type: 'device'; device: string; y: number; ghost: boolean; firmware: string }
  | { type: 'reader'; device: string; reader: string; kind: string; y: number; ghost: boolean };

export interface RightRow {
  track: string;
  kind: string;
  space?: string;
  y: number;
}

export interface Connection {
  index: number;
  sub: SubscriptionConfig;
  fromY: number;
  toY: number;
  problem: SubscriptionProblem | null;
}

export interface SubscriptionLayout {
  left: LeftRow[];
  right: RightRow[];
  connections: Connection[];
  height: number;
}

export function layoutSubscriptions(devices: DeviceView[], subscriptions: SubscriptionConfig[], check: ConfigCheck | null): SubscriptionLayout {
  // Devices: the connected ones, then ghosts for names only the config knows.
  const groups = new Map<string, { ghost: boolean; firmware: string; readers: Array<{ name: string; kind: string }> }>();
  for (const d of devices) {
    if (!d.name) continue;
    groups.set(d.name, { ghost: false, firmware: d.firmware, readers: d.readers.map((r) => ({ name: r.name, kind: r.kind })) });
  }
  for (const s of subscriptions) {
    let g = groups.get(s.device);
    if (!g) groups.set(s.device, (g = { ghost: true, firmware: '', readers: [] }));
    if (!g.readers.some((r) => r.name === s.reader)) g.readers.push({ name: s.reader, kind: 'missing' });
  }
  const left: LeftRow[] = [];
  const readerY = new Map<string, number>();
  // Both columns start under their headings.
  let y = HEAD_H;
  for (const [device, g] of groups) {
    left.push({ type: 'device', device, y, ghost: g.ghost, firmware: g.firmware });
    y += HEAD_H;
    for (const r of g.readers) {
      left.push({ type: 'reader', device, reader: r.name, kind: r.kind, y, ghost: g.ghost || r.kind === 'missing' });
      readerY.set(`${device}\u0000${r.name}`, y + ROW_H / 2);
      y += ROW_H;
    }
    y += GAP;
  }
  const leftHeight = y;

  const right: RightRow[] = [];
  const trackY = new Map<string, number>();
  y = HEAD_H;
  for (const t of check?.tracks ?? []) {
    right.push({ track: t.name, kind: t.kind, space: t.space, y });
    trackY.set(t.name, y + ROW_H / 2);
    y += ROW_H;
  }
  // A subscription to a track the config no longer has still gets drawn, to a ghost row.
  for (const s of subscriptions) {
    if (trackY.has(s.track)) continue;
    right.push({ track: s.track, kind: 'missing', y });
    trackY.set(s.track, y + ROW_H / 2);
    y += ROW_H;
  }

  const problems = new Map<number, SubscriptionProblem>();
  for (const p of check?.subscriptions ?? []) if (!problems.has(p.subscription)) problems.set(p.subscription, p);
  const connections = subscriptions.map((sub, index) => ({
    index,
    sub,
    fromY: readerY.get(`${sub.device}\u0000${sub.reader}`) ?? 0,
    toY: trackY.get(sub.track) ?? 0,
    problem: problems.get(index) ?? null,
  }));
  return { left, right, connections, height: Math.max(leftHeight, y) + 8 };
}
