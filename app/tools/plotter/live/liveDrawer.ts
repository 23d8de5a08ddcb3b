/**
 * Live drawing: pen strokes that the machine follows while they are drawn.
 *
 * Each stroke, as its points arrive from the pointer:
 *
 *   pointer point ─▶ DistanceThinner ─▶ StrokeClipper ─▶ moves ─▶ waiting (FIFO) ─▶ maxl.addSegmentToQueue
 *                    (drop points       (refuse what      travel, pen down,   fed only while
 *                     < tolerance)       leaves the soft   drawTo each point,  queue.hasRoom()
 *                                        limits)           pen up at the end
 *
 * The machine follows while the stroke is being drawn: every kept point becomes a
 * move appended at once to the queue's unplanned tail, the lookahead replans the
 * tail (which always ends at rest at the last known point), and the streamer
 * locks and sends each segment only a lead time before the machine reaches it.
 * So a slow hand is followed at about a braking distance (v²/2a) plus a lead
 * behind, without stopping at each point.
 *
 * A hand faster than the machine runs ahead: the queue fills, and the moves
 * beyond what it holds wait here, in order, and are fed as segments are
 * transmitted and room frees up (the queue's 'transmitted' and 'removed' events;
 * no promise waits inside the core, so STOP never races a waiting move). None is
 * dropped: the machine draws the whole stroke at its limits and catches up.
 *
 * One stroke at a time (one pen). A stroke started while the machine is not ready,
 * or a job, a jog or another tool moves it, is refused with a note in the log
 * (ToolContext.claim). STOP (or Esc) drops every move still waiting and says how
 * many strokes were not drawn.
 */
import type { Maxl, Move, QueueViewEvent, SegmentView } from '../../../../core/index.ts';
import type { LogLevel } from '../../../worker/protocol.ts';
import { drawTo, penDown, penUp, travelTo, type PenSettings } from '../penSequence.ts';
import type { DrawStatus, StrokeProgress } from '../protocol.ts';
import { StrokeClipper, type ClipStep } from './softLimitClip.ts';
import { DistanceThinner, type Point } from './thinning.ts';

/** What the drawer needs of the workbench (a slice of ToolContext). */
export interface LiveHost {
  readonly maxl: Maxl | null;
  /** Takes the machine for drawing; false (with a note in the log) if it cannot. */
  claim(what: string): boolean;
  release(): void;
  log(level: LogLevel, code: string, message: string): void;
  /** The page should drop stroke `id`: nothing of it will be drawn. */
  strokeRefused(id: number, reason: string): void;
}

class LiveStroke {
  /** Pointer points received. */
  received = 0;
  /** Index of the last received point the machine has drawn to, -1 before any. */
  done = -1;
  /** Index of the last received point that became a move (kept by thinning, inside the limits). */
  queuedTo = -1;
  ended = false;
  /** Moves of this stroke not yet finished by the machine. */
  unfinished = 0;
  readonly thinner: DistanceThinner;
  readonly clipper: StrokeClipper;

  constructor(
    readonly id: number,
    readonly pen: PenSettings,
    tolerance_mm: number,
    min: readonly number[],
    max: readonly number[],
  ) {
    this.thinner = new DistanceThinner(tolerance_mm);
    this.clipper = new StrokeClipper(min, max);
  }
}

/** A move on its way to the machine, and where it leaves the stroke. */
interface LiveMove {
  move: Move;
  stroke: LiveStroke;
  /** The received point it draws to, or -1 (travel, pen up or down). */
  pointIndex: number;
  /** mm of path (travel and drawing) from the first live move to this move's start, and its length. */
  pathStart_mm: number;
  length_mm: number;
}

export class LiveDrawer {
  private strokes: LiveStroke[] = [];
  /** The stroke the pointer is drawing, if it is down. */
  private current: LiveStroke | null = null;
  /** Moves waiting for room in the queue, in order; `head` is the next to feed. */
  private waiting: LiveMove[] = [];
  private head = 0;
  /** Moves in the queue, by moveId, until the machine finishes them. */
  private readonly inQueue = new Map<number, LiveMove>();
  /** Where the last move ends (pen axes), mm. */
  private tail: Point | null = null;
  private path_mm = 0;
  private done_mm = 0;
  private holding = false;
  private penRaised = false;
  private maxl: Maxl | null = null;
  private lastId = 0;
  private unsubscribe: (() => void) | null = null;
  /** Counts for the dev/test hook. */
  fedMoves = 0;
  refusedPoints = 0;
  /** Called after every change to the strokes' progress (for the tool's throttled status). */
  onChange: () => void = () => {};

  constructor(private readonly host: LiveHost) {}

  /** Whether strokes are being drawn or waiting (the drawer holds the machine). */
  get active(): boolean {
    return this.holding;
  }

  /** A new author, or none: what was under way on the old one is over. */
  attach(maxl: Maxl | null): void {
    if (this.maxl === maxl) return;
    if (this.maxl) this.discard('the machine was reconfigured');
    this.unsubscribe?.();
    this.unsubscribe = null;
    this.maxl = maxl;
    this.penRaised = false;
    if (maxl) this.unsubscribe = maxl.queue.subscribe((e) => this.onQueue(e));
  }

  /** The pointer went down at p: a new stroke, if the machine can be had. False if refused. */
  start(id: number, p: Point, pen: PenSettings | null, tolerance_mm: number): boolean {
    this.lastId = Math.max(this.lastId, id);
    const refuse = (reason: string, level: LogLevel = 'warning') => {
      this.refusedPoints++;
      this.host.log(level, 'DRAW_REFUSED', `Stroke not drawn: ${reason}.`);
      this.host.strokeRefused(id, reason);
      return false;
    };
    if (this.current) return refuse('one stroke at a time: lift the other pointer first');
    if (!pen) return refuse('this machine has no event channel to drive a pen (Configure → Events)');
    const maxl = this.host.maxl;
    // claim() writes its own note (not ready, or who moves the machine).
    if (!maxl || !this.host.claim('draw a stroke')) {
      this.refusedPoints++;
      this.host.strokeRefused(id, 'the machine is not ready, or a job, a jog or another tool moves it (the log says which)');
      return false;
    }
    this.attach(maxl);
    this.holding = true;
    const axes = pen.axes.map((a) => maxl.config.motionAxes.indexOf(a));
    const stroke = new LiveStroke(
      id,
      pen,
      tolerance_mm,
      axes.map((a) => maxl.config.softMin[a]),
      axes.map((a) => maxl.config.softMax[a]),
    );
    if (this.tail === null) this.tail = [maxl.nextMoveStart[axes[0]], maxl.nextMoveStart[axes[1]]];
    // Whatever state a job or a jog left the pen in, the first stroke starts with it up.
    if (!this.penRaised) {
      this.enqueue(penUp(pen), stroke, -1, 0);
      this.penRaised = true;
    }
    this.strokes.push(stroke);
    this.current = stroke;
    this.take(stroke, p);
    this.feed();
    return true;
  }

  /** More points of stroke `id` (x, y pairs), in order. Points of a refused or discarded stroke are ignored. */
  points(id: number, xy: ArrayLike<number>, stride = 2): void {
    const s = this.current;
    if (!s || s.id !== id) {
      this.refusedPoints += Math.floor(xy.length / stride);
      return;
    }
    for (let i = 0; i + 1 < xy.length; i += stride) this.take(s, [xy[i], xy[i + 1]]);
    this.feed();
  }

  /** The pointer lifted: the stroke ends at its last point, pen up. */
  end(id: number): void {
    const s = this.current;
    if (!s || s.id !== id) return;
    const last = s.thinner.finish();
    if (last) this.place(s, last, s.received - 1);
    for (const step of s.clipper.finish()) this.apply(s, step, s.received - 1);
    s.ended = true;
    this.current = null;
    if (s.clipper.refused_mm > 0) {
      const [x, y] = s.clipper.firstRefused ?? [NaN, NaN];
      const { min: lo, max: hi } = s.clipper;
      this.host.log(
        'warning',
        'DRAW_OUTSIDE',
        `Stroke ${id} left the soft limits (first point outside: ${x.toFixed(1)}, ${y.toFixed(1)} mm; the bed is ${lo[0]}–${hi[0]} × ${lo[1]}–${hi[1]} mm): ${s.clipper.refused_mm.toFixed(1)} mm outside were not drawn, the rest was.`,
      );
    }
    this.feed();
    this.settle();
  }

  /** STOP: every device halted. Drops what waits, and says what was not drawn. */
  stopped(): void {
    this.discard('STOP');
  }

  /** The strokes still being drawn, and how far behind the machine is. */
  status(): DrawStatus {
    const strokes: StrokeProgress[] = this.strokes.map((s) => ({ id: s.id, received: s.received, done: s.done, ended: s.ended }));
    const behind_mm = Math.max(0, this.path_mm - this.done_mm);
    const speed = this.current?.pen.drawSpeed ?? this.strokes.at(-1)?.pen.drawSpeed ?? NaN;
    return { strokes, waitingMoves: this.waiting.length - this.head, behind_mm, behind_s: behind_mm / speed || 0, active: this.holding, lastId: this.lastId };
  }

  /** Releases the machine once everything drawn has run (call now and then: the tool's frame). */
  settle(): void {
    const maxl = this.maxl;
    if (!this.holding || this.current || this.head < this.waiting.length || !maxl) return;
    const q = maxl.queue;
    if (q.untransmittedCount > 0 || q.transmittedEnd_us > maxl.scheduler.now()) return;
    this.holding = false;
    this.strokes = [];
    this.inQueue.clear();
    this.host.release();
    this.onChange();
  }

  // --- from points to moves ---

  private take(s: LiveStroke, p: Point): void {
    const index = s.received++;
    if (s.thinner.push(p)) this.place(s, p, index);
  }

  private place(s: LiveStroke, p: Point, index: number): void {
    for (const step of s.clipper.push(p)) this.apply(s, step, index);
  }

  private apply(s: LiveStroke, step: ClipStep, index: number): void {
    if (step.type === 'start') {
      this.enqueue(travelTo(step.p, s.pen), s, -1, this.distanceTo(step.p));
      this.tail = step.p;
      this.enqueue(penDown(s.pen), s, index, 0);
      s.queuedTo = index;
    } else if (step.type === 'to') {
      this.enqueue(drawTo(step.p, s.pen), s, index, this.distanceTo(step.p));
      this.tail = step.p;
      s.queuedTo = index;
    } else {
      this.enqueue(penUp(s.pen), s, -1, 0);
    }
  }

  private distanceTo(p: Point): number {
    return this.tail ? Math.hypot(p[0] - this.tail[0], p[1] - this.tail[1]) : 0;
  }

  private enqueue(move: Move, stroke: LiveStroke, pointIndex: number, length_mm: number): void {
    this.waiting.push({ move, stroke, pointIndex, pathStart_mm: this.path_mm, length_mm });
    this.path_mm += length_mm;
    stroke.unfinished++;
  }

  /** Hands waiting moves to the queue while it has room, in order. */
  private feed(): void {
    const maxl = this.maxl;
    if (!maxl) return;
    const queue = maxl.queue;
    while (this.head < this.waiting.length && queue.hasRoom()) {
      const m = this.waiting[this.head++];
      this.fedMoves++;
      maxl.addSegmentToQueue(m.move).then(
        (receipt) => {
          if (receipt.skipped) this.finished(m, m.length_mm);
          else this.inQueue.set(receipt.moveId, m);
        },
        (err: unknown) => this.failed(m, err),
      );
    }
    if (this.head === this.waiting.length) {
      this.waiting = [];
      this.head = 0;
    } else if (this.head > 4096) {
      this.waiting = this.waiting.slice(this.head);
      this.head = 0;
    }
  }

  private onQueue(e: QueueViewEvent): void {
    if (e.type === 'transmitted' || e.type === 'removed') {
      if (this.head < this.waiting.length) this.feed();
    } else if (e.type === 'historical') {
      for (const seg of e.segments) this.segmentDone(seg);
      this.onChange();
    }
  }

  /** The machine finished a segment: a whole move when it reaches the move's end (the streamer may have sliced it). */
  private segmentDone(seg: SegmentView): void {
    const m = this.inQueue.get(seg.moveId);
    if (!m) return;
    const along = seg.moveOffset + seg.length;
    this.done_mm = Math.max(this.done_mm, m.pathStart_mm + Math.min(along, m.length_mm));
    if (along >= m.length_mm - 1e-9) {
      this.inQueue.delete(seg.moveId);
      this.finished(m, m.length_mm);
    }
  }

  private finished(m: LiveMove, length_mm: number): void {
    this.done_mm = Math.max(this.done_mm, m.pathStart_mm + length_mm);
    const s = m.stroke;
    if (m.pointIndex > s.done) s.done = m.pointIndex;
    s.unfinished--;
    if (s.ended && s.unfinished === 0) {
      s.done = s.received - 1;
      this.strokes = this.strokes.filter((x) => x !== s);
    }
  }

  private failed(m: LiveMove, err: unknown): void {
    const message = err instanceof Error ? err.message : String(err);
    this.host.log('error', 'DRAW_FAILED', `Stroke ${m.stroke.id}: the machine refused a move (${message}).`);
    this.discard('the failed move');
  }

  /** Drops every stroke not yet drawn, with a note naming how many. */
  private discard(why: string): void {
    const waitingMoves = this.waiting.length - this.head;
    const notDrawn = this.strokes.filter((s) => s.unfinished > 0 || !s.ended);
    if (notDrawn.length > 0 || waitingMoves > 0) {
      const ids = notDrawn.map((s) => s.id);
      this.host.log(
        'warning',
        'DRAW_DISCARDED',
        `${why}: ${ids.length} stroke${ids.length === 1 ? '' : 's'} not drawn to the end (${ids.join(', ')}) discarded, with ${waitingMoves} move${waitingMoves === 1 ? '' : 's'} that were waiting.`,
      );
    }
    this.waiting = [];
    this.head = 0;
    this.strokes = [];
    this.current = null;
    this.inQueue.clear();
    this.tail = null;
    this.path_mm = this.done_mm = 0;
    if (this.holding) this.host.release();
    this.holding = false;
    this.onChange();
  }
}
