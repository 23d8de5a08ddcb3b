/**
 * Says so in the log when real boards' lead has grown because the computer held
 * the worker back. The streamer follows the machine (core/net/streamer.ts,
 * `lagAllowance_us`): after a hold-back it keeps more motion sent ahead, for 10 s,
 * so that the next one does not run the boards out. That is safe, but a jog then
 * starts and stops later by as much; the user should know why, and what helps.
 *
 * Once the lead is LEAD_GROWTH_US above the lead the author had when it became
 * ready, at most once every NOTE_EVERY_US.
 */
import type { LogNote } from './runtimeNotes.ts';

/** How far above the lead at ready (µs) the lead must grow to be worth a note: a jog ~30 ms later is felt. */
export const LEAD_GROWTH_US = 30_000;
/** At most one note this often (µs): a loaded machine holds the worker back again and again. */
export const NOTE_EVERY_US = 30_000_000;

export class LeadWatch {
  private quiet_us = NaN;
  private lastNote_us = -Infinity;

  /** A new author became ready with this lead (µs); NaN where margins do not follow the machine (simulated machines). */
  ready(lead_us: number): void {
    this.quiet_us = lead_us;
    this.lastNote_us = -Infinity;
  }

  /** The lead at `now_us`: a note if it has grown enough and none was given lately. */
  check(now_us: number, lead_us: number): LogNote | null {
    if (!(lead_us >= this.quiet_us + LEAD_GROWTH_US) || now_us - this.lastNote_us < NOTE_EVERY_US) return null;
    this.lastNote_us = now_us;
    const ms = (us: number) => (us / 1000).toFixed(0);
    return {
      level: 'warning',
      code: 'LEAD',
      message: `The computer held the MAXL worker back, so real boards are now streamed ${ms(lead_us)} ms ahead (${ms(this.quiet_us)} ms when they became ready), until 10 s after the last hold-back: jogs start and stop that much later. Closing busy programs or tabs brings it back down.`,
    };
  }
}
