/**
 * Checks a machine configuration for the editor, subscription by subscription,
 * against the devices that said hello: every problem is reported on the
 * subscription it belongs to, so that the editor can say it where it draws it.
 * (The core's own begin() refuses the same mismatches, all in one error.)
 */
import { MaxlError, resolveConfig, type SubscriptionConfig } from '../../core/index.ts';
import { bindSubscriptions } from '../../core/net/bindings.ts';
import type { DeviceInfo } from '../../core/index.ts';
import type { ConfigCheck, MachineConfig, SubscriptionProblem } from './protocol.ts';

export function checkConfig(config: MachineConfig, devices: DeviceInfo[], requestId: number): ConfigCheck {
  const subscriptions = config.subscriptions ?? [];
  let resolved;
  try {
    resolved = resolveConfig({ ...config, subscriptions: [] });
  } catch (err) {
    return { requestId, error: fieldError(err), subscriptions: [], tracks: [] };
  }
  const tracks = resolved.tracks.map((t) => ({ name: t.name, kind: t.kind, space: t.space }));
  const trackNames = new Set(tracks.map((t) => t.name));
  const problems: SubscriptionProblem[] = [];
  const usable: Array<{ index: number; sub: SubscriptionConfig }> = [];
  const readerOwner = new Map<string, number>();
  subscriptions.forEach((sub, index) => {
    if (!trackNames.has(sub.track)) {
      problems.push({ subscription: index, problem: 'unknown track', message: `"${sub.track}" is not a track of this machine` });
      return;
    }
    const key = `${sub.device}\u0000${sub.reader}`;
    const owner = readerOwner.get(key);
    if (owner !== undefined) {
      problems.push({
        subscription: index,
        problem: 'reader used twice',
        message: `reader "${sub.reader}" of "${sub.device}" already reads "${subscriptions[owner].track}": one reader reads one track`,
      });
      return;
    }
    readerOwner.set(key, index);
    usable.push({ index, sub });
  });
  if (devices.length > 0) {
    const { mismatches } = bindSubscriptions({ ...resolved, subscriptions: usable.map((u) => u.sub) }, devices);
    for (const m of mismatches) {
      const index = usable[m.subscription].index;
      problems.push({ subscription: index, problem: m.problem, message: m.message.replace(/^subscriptions\[\d+\]: /, '') });
    }
  }
  let error: ConfigCheck['error'] = null;
  try {
    resolveConfig(config);
  } catch (err) {
    error = fieldError(err);
  }
  problems.sort((a, b) => a.subscription - b.subscription);
  return { requestId, error, subscriptions: problems, tracks };
}

function fieldError(err: unknown): { field: string; message: string } {
  if (err instanceof MaxlError) return { field: err.field ?? '', message: err.message };
  return { field: '', message: String(err) };
}
