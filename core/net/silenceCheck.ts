/**
 * The session's health check: is a device silent for too long (its link lost)?
 *
 * The check runs on a timer every silence/4. When that timer runs far behind its
 * time, the author's own thread was held back (a frozen tab, a machine loaded by
 * other work, a long garbage collection): the device's frames from that time may
 * still wait in the thread's queue, behind this very timer, and the silence it
 * measures is the author's, not the device's. Such a check judges nothing and
 * checks again one period later, when those frames are in; only once, so that a
 * thread held back at every check still finds a lost link, a period later.
 */

export type SilenceVerdict = 'quiet-enough' | 'lost' | 'held-back';

export interface SilenceCheck {
  /** now (µs, author clock) */
  now_us: number;
  /** when this check was due (µs) */
  due_us: number;
  /** the last frame heard from the device (µs) */
  lastHeard_us: number;
  /** silence that means a lost link (µs); checks run every quarter of it */
  silence_us: number;
  /** whether the previous check was held back already */
  previousHeldBack: boolean;
}

export function silenceVerdict(c: SilenceCheck): SilenceVerdict {
  if (c.now_us - c.lastHeard_us <= c.silence_us) return 'quiet-enough';
  const period = c.silence_us / 4;
  if (c.now_us - c.due_us > period && !c.previousHeldBack) return 'held-back';
  return 'lost';
}
