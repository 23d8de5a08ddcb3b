/**
 * The pen settings a plotter starts with, from the machine's configuration.
 *
 * Pen channel: the event channel named "pen" if the machine has one (the Blot
 * preset does), else its first event channel; null when it has none (no pen to
 * drive: the plotter tool says so and draws nothing).
 *
 * Up 0, down 1: the BlotPlotter firmware's pen reader maps 0 → 1000 µs (up) and
 * 1 → 1900 µs (down); a board of your own maps its values the same way, or you
 * set other values in the panel (axicli's pen_pos_up / pen_pos_down).
 *
 * Delays (axicli's pen_delay_down / pen_delay_up, here the dwell after each pen
 * command): the servo must land before the stroke starts and leave the paper
 * before the carriage travels. The dwell starts when the event is due on the
 * device, so it must cover the servo's swing plus the wait for its next pulse
 * frame: a hobby servo reads its pulse width every 20 ms (50 Hz), so a new width
 * takes effect up to 20 ms late. On the simulated Blot the servo drops in 120 ms
 * and lifts in 90 ms, so: down 120 + 20 + 10 ms margin = 150 ms, up 90 + 20 + 10
 * = 120 ms. On real boards, with an SG90-class servo (~0.1 s per 60° at 4.8 V)
 * and a pen holder whose swing is not known: 250 ms both ways, a safe start to
 * tune down from (axicli's pen_rate plays that part there).
 *
 * Speeds: live drawing follows the hand, and a machine that falls behind should
 * catch up as fast as it can, so the draw speed defaults to the machine's speed
 * limit; travel (pen up) too. Lower them in the panel for a pen that skips.
 */
import type { PenSettings } from './penSequence.ts';

export interface PenMachine {
  motionAxes: readonly string[];
  eventChannels?: readonly string[];
  limits: { maxVelocity: number };
}

/** The simulated Blot's servo: drop 120 ms, lift 90 ms (core/sim/presets/blotPlotter.ts). */
const BLOT_DELAYS = { delayDown_s: 0.15, delayUp_s: 0.12 };
/** A real board's servo of unknown swing. */
const REAL_BOARD_DELAYS = { delayDown_s: 0.25, delayUp_s: 0.25 };

/** The default distance between kept points of a live stroke, mm. */
export const DEFAULT_TOLERANCE_MM = 0.2;

export function penChannel(machine: PenMachine): string | null {
  const channels = machine.eventChannels ?? [];
  if (channels.includes('pen')) return 'pen';
  return channels[0] ?? null;
}

/** Pen settings for this machine; null when it has no event channel to drive a pen. */
export function penDefaults(machine: PenMachine, presetId: string | null): PenSettings | null {
  const channel = penChannel(machine);
  if (channel === null || machine.motionAxes.length < 2) return null;
  const delays = presetId === 'blotPlotter' ? BLOT_DELAYS : REAL_BOARD_DELAYS;
  return {
    channel,
    up: 0,
    down: 1,
    ...delays,
    drawSpeed: machine.limits.maxVelocity,
    travelSpeed: machine.limits.maxVelocity,
    axes: [machine.motionAxes[0], machine.motionAxes[1]],
  };
}

/**
 * What is wrong with edited settings, in words, or null if they are fine. Every
 * field is checked before any is applied: nothing is half-applied.
 */
export function penSettingsProblem(s: PenSettings, machine: PenMachine): string | null {
  const channels = machine.eventChannels ?? [];
  if (!channels.includes(s.channel)) return `"${s.channel}" is not an event channel of this machine (${channels.join(', ') || 'it has none'})`;
  for (const [name, v] of [['pen up value', s.up], ['pen down value', s.down]] as const) if (!Number.isFinite(v)) return `the ${name} must be a number`;
  for (const [name, v] of [['pen-up delay', s.delayUp_s], ['pen-down delay', s.delayDown_s]] as const) {
    if (!Number.isFinite(v) || v < 0 || v > 10) return `the ${name} must be between 0 and 10 s, got ${v}`;
  }
  for (const [name, v] of [['draw speed', s.drawSpeed], ['travel speed', s.travelSpeed]] as const) {
    if (!Number.isFinite(v) || v <= 0) return `the ${name} must be above 0 mm/s, got ${v}`;
  }
  if (s.axes.some((a) => !machine.motionAxes.includes(a)) || s.axes[0] === s.axes[1]) return `the pen draws in two different motion axes of ${machine.motionAxes.join(', ')}`;
  return null;
}
