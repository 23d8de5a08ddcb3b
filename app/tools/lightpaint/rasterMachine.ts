/** What the raster planner needs of a configured author: limits along +x, soft limits, channels. */
import { projectLimit } from '../../../core/config/limits.ts';
import type { ResolvedConfig } from '../../../core/index.ts';
import type { RasterMachine } from './raster.ts';

export function rasterMachine(config: ResolvedConfig, origin: readonly number[]): RasterMachine {
  const unitX = config.motionAxes.map((_, i) => (i === 0 ? 1 : 0));
  return {
    motionAxes: config.motionAxes,
    eventChannels: config.eventChannels,
    origin,
    softMin: config.softMin,
    softMax: config.softMax,
    maxSpeed: projectLimit(config.limits.maxSpeed, config.limits.axisMaxSpeed, unitX),
    maxAccel: projectLimit(config.limits.maxAccel, config.limits.axisMaxAccel, unitX),
  };
}
