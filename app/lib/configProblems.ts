/**
 * Every problem of a machine configuration, not only the first: the core's own
 * validation (resolveConfig, the one source of truth) run on each part of the
 * config on its own, with the other parts replaced by something valid, and then
 * on the whole (for what only the whole shows: a name used twice across parts,
 * the subscriptions). The editor lists them all, and Apply waits until none is left.
 */
import { MaxlError, resolveConfig, type MaxlConfig } from '../../core/index.ts';
import type { MachineConfig } from '../worker/protocol.ts';

export interface ConfigProblem {
  /** The config field, as the core names it: "limits.maxVelocity", "softLimits.x". */
  field: string;
  message: string;
}

const VALID_LIMITS = { maxVelocity: 1, maxAcceleration: 1 };

export function configProblems(config: MachineConfig): ConfigProblem[] {
  const problems: ConfigProblem[] = [];
  const seen = new Set<string>();
  /** Checks one part; `rename` maps the field the part's error names to the whole config's. */
  const check = (part: MaxlConfig, rename: (field: string) => string = (f) => f) => {
    try {
      resolveConfig(part);
    } catch (err) {
      const p = err instanceof MaxlError ? { field: rename(err.field ?? ''), message: err.message.split(err.field ?? '\u0000').join(rename(err.field ?? '')) } : { field: '', message: String(err) };
      const key = `${p.field}\u0000${p.message}`;
      if (!seen.has(key)) {
        seen.add(key);
        problems.push(p);
      }
    }
  };
  const motionAxes = config.motionAxes;
  check({ motionAxes, limits: VALID_LIMITS });
  if (problems.length === 0) {
    const limits = config.limits ?? {};
    for (const key of Object.keys(limits) as Array<keyof typeof limits>) check({ motionAxes, limits: { ...VALID_LIMITS, [key]: limits[key] } });
    for (const [axis, range] of Object.entries(config.softLimits ?? {})) check({ motionAxes, limits: VALID_LIMITS, softLimits: { [axis]: range } });
    (config.transforms ?? []).forEach((t, i) => {
      // Checked alone, a transform is transforms[0]: name it by its own place.
      check({ motionAxes, limits: VALID_LIMITS, transforms: [t] }, (f) => f.replace(/^transforms\[0\]/, `transforms[${i}]`));
    });
    if (config.eventChannels) check({ motionAxes, limits: VALID_LIMITS, eventChannels: config.eventChannels });
  }
  check(config);
  return problems;
}
