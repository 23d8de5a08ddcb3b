/**
 * Turns one MAXL author's queue into snapshots for the view, cheaply enough to
 * run every animation frame while 100 000-segment jobs stream:
 *
 *   - transmitted segments are locked and append-only: each snapshot carries only
 *     those locked since the last one, as vertices (2 per segment, x y z);
 *   - historical segments are always the oldest locked ones, so a count says which;
 *   - untransmitted segments (planned and unplanned, at most a queue's capacity)
 *     are sent whole, and only when the queue changed.
 */
import type { Maxl, QueueViewEvent, SegmentView } from '../../core/index.ts';
import { GrowableFloats } from './growableFloats.ts';
import { QUEUE_PLANNED, QUEUE_UNPLANNED } from './protocol.ts';

/** At most this many untransmitted segments are drawn (the queue's default capacity is 512). */
const MAX_QUEUE_DRAWN = 4096;

export interface LockedSegmentListener {
  (seg: SegmentView): void;
}

export class SnapshotBuilder {
  private maxl: Maxl | null = null;
  private unsubscribe: (() => void) | null = null;
  private locked = new GrowableFloats();
  private lockedCount = 0;
  private lockedSent = 0;
  private historical = 0;
  private queueDirty = true;
  /** Hears every segment that becomes historical (for job progress). */
  onHistorical: ((seg: SegmentView) => void) | null = null;

  /** Follows a new author from scratch. */
  attach(maxl: Maxl | null): void {
    this.unsubscribe?.();
    this.unsubscribe = null;
    this.maxl = maxl;
    this.locked.clear();
    this.lockedCount = 0;
    this.lockedSent = 0;
    this.historical = 0;
    this.queueDirty = true;
    if (maxl) this.unsubscribe = maxl.queue.subscribe((e) => this.onQueue(e));
  }

  private onQueue(e: QueueViewEvent): void {
    switch (e.type) {
      case 'transmitted':
        for (const seg of e.segments) {
          this.pushPoint(seg.start);
          this.pushPoint(seg.end);
          this.lockedCount++;
        }
        this.queueDirty = true;
        break;
      case 'historical':
        this.historical += e.segments.length;
        if (this.onHistorical) for (const seg of e.segments) this.onHistorical(seg);
        break;
      default:
        this.queueDirty = true;
    }
  }

  private pushPoint(p: readonly number[]): void {
    this.locked.push3(p[0] ?? 0, p[1] ?? 0, p[2] ?? 0);
  }

  /** Locked segments since the last call: where they start in the locked path, and their vertices. */
  takeLocked(): { from: number; vertices: Float32Array } {
    const from = this.lockedSent;
    this.lockedSent = this.lockedCount;
    return { from, vertices: this.locked.take() };
  }

  get historicalCount(): number {
    return this.historical;
  }

  /** The untransmitted segments and their states, or nulls if nothing changed since the last call. */
  takeQueue(): { vertices: Float32Array | null; states: Uint8Array | null } {
    if (!this.queueDirty || !this.maxl) return { vertices: null, states: null };
    this.queueDirty = false;
    const segments = this.maxl.queue.segments();
    const pending = segments.filter((s) => s.state === 'planned' || s.state === 'unplanned').slice(0, MAX_QUEUE_DRAWN);
    const vertices = new Float32Array(pending.length * 6);
    const states = new Uint8Array(pending.length);
    pending.forEach((seg, i) => {
      const o = i * 6;
      vertices[o] = seg.start[0] ?? 0;
      vertices[o + 1] = seg.start[1] ?? 0;
      vertices[o + 2] = seg.start[2] ?? 0;
      vertices[o + 3] = seg.end[0] ?? 0;
      vertices[o + 4] = seg.end[1] ?? 0;
      vertices[o + 5] = seg.end[2] ?? 0;
      states[i] = seg.state === 'planned' ? QUEUE_PLANNED : QUEUE_UNPLANNED;
    });
    return { vertices, states };
  }
}
