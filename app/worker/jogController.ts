/**
 * Jogging on the author: steps, and hold-to-jog.
 *
 * Hold-to-jog queues one long move toward the soft limit (or far away) in the
 * held direction. The streamer locks only a few ms of it at a time (minimal
 * buffering, with long segments sliced at the horizon), so on release
 * `cancel()` can brake right after the little that is locked, at the
 * acceleration limit, and drop the rest.
 *
 * The stop latency is measured on the plan, in author time: from the release
 * (the input event's timestamp, carried from the page) to where braking starts
 * (the end of the path that was already locked), and to rest.
 */
import type { Maxl } from '../../core/index.ts';
import type { JogStopReport } from './protocol.ts';

/** How far a held jog reaches when an axis has no soft limit, mm. */
const UNBOUNDED_REACH_MM = 10_000;

export interface JogHost {
  warn(code: string, message: string): void;
  report(r: JogStopReport): void;
}

/** ms since the epoch, on the same clock as the page's (performance.timeOrigin + now()). */
export function epochNow(): number {
  return performance.timeOrigin + performance.now();
}

export class JogController {
  private holding: Maxl | null = null;

  constructor(private readonly host: JogHost) {}

  get isHolding(): boolean {
    return this.holding !== null;
  }

  step(maxl: Maxl, delta: readonly number[], speed: number): void {
    const from = maxl.nextMoveStart;
    const target = from.map((p, i) => p + (delta[i] ?? 0));
    this.move(maxl, target, speed);
  }

  moveTo(maxl: Maxl, target: readonly number[], speed: number): void {
    this.move(maxl, [...target], speed);
  }

  start(maxl: Maxl, direction: readonly number[], speed: number): void {
    if (this.holding) return;
    const from = maxl.nextMoveStart;
    const norm = Math.hypot(...direction);
    if (!(norm > 0)) return;
    const unit = direction.map((d) => d / norm);
    // Reach: up to the nearest soft limit along the direction (a little inside it).
    let reach = UNBOUNDED_REACH_MM;
    const { softMin, softMax } = maxl.config;
    unit.forEach((u, i) => {
      if (u > 0 && Number.isFinite(softMax[i])) reach = Math.min(reach, (softMax[i] - from[i]) / u);
      if (u < 0 && Number.isFinite(softMin[i])) reach = Math.min(reach, (softMin[i] - from[i]) / u);
    });
    if (reach < 0.01) {
      this.host.warn('SOFT_LIMIT', 'Already at the soft limit in that direction: jog the other way, or widen the soft limits in Configure → Axes.');
      return;
    }
    this.holding = maxl;
    this.move(maxl, from.map((p, i) => p + unit[i] * reach), speed);
  }

  /** Release: brake now and drop the rest of the held move. */
  async stop(releasedAt_ms: number): Promise<void> {
    const maxl = this.holding;
    if (!maxl) return;
    this.holding = null;
    const now = maxl.scheduler.now();
    const delivery_ms = Math.max(0, epochNow() - releasedAt_ms);
    const release_us = now - delivery_ms * 1000;
    const lockedAhead_ms = Math.max(0, maxl.queue.transmittedEnd_us - now) / 1000;
    const speed = maxl.sample(release_us).speed;
    const cancelled = maxl.cancel();
    // cancel() has planned the stop synchronously: braking starts where the locked path ends.
    const brakeStart_us = Math.max(now, Math.min(maxl.queue.transmittedEnd_us, Number.MAX_VALUE));
    await cancelled;
    const rest_us = Math.max(brakeStart_us, maxl.queue.transmittedEnd_us);
    this.host.report({
      speed,
      brakeLatency_ms: (brakeStart_us - release_us) / 1000,
      restLatency_ms: (rest_us - release_us) / 1000,
      braking_ms: (rest_us - brakeStart_us) / 1000,
      delivery_ms,
      lockedAhead_ms,
      lead_ms: maxl.lead_us / 1000,
    });
  }

  /** The machine changed under the jog (STOP, a new runtime): forget the held move. */
  reset(): void {
    this.holding = null;
  }

  private move(maxl: Maxl, target: number[], speed: number): void {
    maxl.addSegmentToQueue({ endPosition: target, maxVelocity: speed }).catch((err: unknown) => {
      this.holding = null;
      const e = err as { code?: string; message?: string };
      this.host.warn(e.code ?? 'JOG', `Jog refused: ${e.message ?? String(err)}`);
    });
  }
}
