/**
 * The pen-down path of the plan, as it is locked: "Save as planned (SVG)".
 *
 * Every segment the streamer transmits carries the event channels' values as it
 * begins (`eventsAtStart`). A transmitted segment that moves while the pen channel
 * is nearer its down value than its up value is planned ink; consecutive ones
 * make one stroke, and any segment with the pen up (a pen-up dwell, a travel)
 * ends it. Slices of one move (the streamer locks long moves in slices) simply
 * continue the stroke.
 */
import type { Maxl, QueueViewEvent, SegmentView } from '../../../../core/index.ts';

export class PlannedPen {
  /** Pen-down strokes, x, y pairs in machine mm. */
  strokes: number[][] = [];
  private open = false;
  private channel = -1;
  private axes: [number, number] = [0, 1];
  private unsubscribe: (() => void) | null = null;

  constructor(private readonly pen: () => { channel: string; up: number; down: number; axes: readonly [string, string] } | null) {}

  /** Follows a new author's transmitted segments (or stops following: null). */
  attach(maxl: Maxl | null): void {
    this.unsubscribe?.();
    this.unsubscribe = null;
    this.open = false;
    if (!maxl) return;
    this.unsubscribe = maxl.queue.subscribe((e) => this.onQueue(e, maxl));
  }

  clear(): void {
    this.strokes = [];
    this.open = false;
  }

  private onQueue(e: QueueViewEvent, maxl: Maxl): void {
    if (e.type !== 'transmitted') return;
    const pen = this.pen();
    if (!pen) return;
    this.channel = maxl.config.eventChannels.indexOf(pen.channel);
    this.axes = [maxl.config.motionAxes.indexOf(pen.axes[0]), maxl.config.motionAxes.indexOf(pen.axes[1])];
    if (this.channel < 0 || this.axes[0] < 0 || this.axes[1] < 0) return;
    for (const seg of e.segments) this.add(seg, pen);
  }

  private add(seg: SegmentView, pen: { up: number; down: number }): void {
    const value = seg.eventsAtStart?.[this.channel] ?? pen.up;
    const down = Math.abs(value - pen.down) < Math.abs(value - pen.up);
    if (!down) {
      this.open = false;
      return;
    }
    if (seg.length === 0) return; // the pen-down dwell: the stroke starts with the first move
    const [a, b] = this.axes;
    if (!this.open) {
      this.strokes.push([seg.start[a], seg.start[b]]);
      this.open = true;
    }
    this.strokes[this.strokes.length - 1].push(seg.end[a], seg.end[b]);
  }
}
