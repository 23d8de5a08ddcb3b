/**
 * Runs one job at a time on the author: checks it against the soft limits, shows
 * its whole path, feeds its moves into the bounded queue as room frees up, and
 * follows its progress from the segments that finish.
 *
 * The feed hands the queue runs of moves with the batch API (maxl.addSegmentsNow:
 * as many as fit, synchronously, no promise per move), and awaits addSegmentToQueue
 * for the move that finds no room (it waits until there is), then whenIdle. Each run
 * has an AbortController whose signal both waits take: a cancel, a STOP or a failure
 * aborts it first, so a move still waiting for room is dropped, never queued behind
 * the stop; no timer polls for either. A move the core refuses stops the job with
 * the job's own words for it: which move, and where it comes from in the user's
 * file when the tool said (MoveJob.describeMove, jobMoveError.ts).
 */
import { batchItemOf, isDwell, isMoveError, MaxlError, type Maxl, type Move, type SegmentView } from '../../core/index.ts';
import { errorWords } from './errorWords.ts';
import { jobMoveError } from './jobMoveError.ts';
import { patternPoints } from './jobPatterns.ts';
import type { JobPhase, JobProgress, JobRequest, LogLevel } from './protocol.ts';
import { yieldToEvents } from './yieldToEvents.ts';

export interface JobHost {
  log(level: LogLevel, code: string, message: string): void;
  /** The job's whole path: (n + 1) × 3 vertices, the tool's start first. */
  preview(name: string, points: Float32Array, segments: number): void;
}

/**
 * A job that a tool built in the worker: any moves (dwells and events too), with
 * the planner's own duration for its ETA when the tool knows it.
 */
export interface MoveJob {
  name: string;
  moves: readonly Move[];
  /** s, the plan's duration (planPath), for the ETA; else the ETA follows the speed so far. */
  planned_s?: number;
  /**
   * Where moves[index] comes from, in the user's words (`line 12 of plot.gcode`), for
   * the error if the core refuses it; absent when the tool cannot say.
   */
  describeMove?: (index: number) => string | null;
}

interface Run {
  name: string;
  maxl: Maxl;
  /**
   * The job's moves from the i-th on, as an array and the index of move i in it:
   * the job's own array (a tool's job), or a run of moves made for it (a points job).
   */
  movesFrom: (i: number) => { moves: readonly Move[]; at: number };
  /** Where the i-th move comes from in the user's words, or null. */
  describeMove: (i: number) => string | null;
  count: number;
  /** mm/s: the ETA's rate until 0.2 s of motion have run. */
  maxVelocity: number;
  planned_s: number;
  phase: JobPhase;
  /** No more moves are fed once set (cancel, STOP, a failure). */
  stopped: boolean;
  /** Gives up the run's waits (STOP, a halt, a lost machine); a resumed run gets a fresh one. */
  abort: AbortController;
  /** Resolves the wait of a paused run, on resume. */
  wake: (() => void) | null;
  fed: number;
  firstMoveId: number;
  lastDoneMoveId: number;
  totalLength: number;
  doneLength: number;
  /** s of motion of the finished segments */
  motion_s: number;
  /** Stopped off its plan (a lost link, a restart, STOP): resumable from where it stopped (resumeAfterStop). */
  resumable: boolean;
}

/** Feed at most this long (ms) before letting commands in. */
const FEED_SLICE_MS = 4;
/** Moves made at a time for a points job (its moves are made as they are fed). */
const POINTS_RUN = 256;

export class JobRunner {
  private run: Run | null = null;

  constructor(private readonly host: JobHost) {}

  /** Whether a job holds the machine (jogs wait until it ends). */
  get active(): boolean {
    const p = this.run?.phase;
    return p === 'loading' || p === 'running' || p === 'pausing' || p === 'paused' || p === 'cancelling';
  }

  get fed(): number {
    return this.run?.fed ?? 0;
  }

  progress(): JobProgress | null {
    const r = this.run;
    if (!r) return null;
    const doneSegments = r.firstMoveId > 0 && r.lastDoneMoveId >= r.firstMoveId ? r.lastDoneMoveId - r.firstMoveId + 1 : 0;
    const remaining = Math.max(0, r.totalLength - r.doneLength);
    const rate = r.motion_s > 0.2 ? r.doneLength / r.motion_s : r.maxVelocity;
    const finished = r.phase === 'done' || r.phase === 'cancelled' || r.phase === 'halted' || r.phase === 'failed';
    const eta_s = finished ? 0 : r.planned_s > 0 ? Math.max(0, r.planned_s - r.motion_s) : rate > 0 ? remaining / rate : NaN;
    return {
      name: r.name,
      phase: r.phase,
      totalSegments: r.count,
      doneSegments: Math.min(r.count, doneSegments),
      totalLength: r.totalLength,
      doneLength: Math.min(r.totalLength, r.doneLength),
      eta_s,
      elapsed_s: r.motion_s,
      resumable: r.resumable,
    };
  }

  start(request: JobRequest, maxl: Maxl, origin: readonly number[]): void {
    if (this.active) {
      this.host.log('warning', 'JOB_BUSY', `“${this.run?.name}” is still running: cancel it first, or wait until it ends.`);
      return;
    }
    const axes = maxl.config.motionAxes.length;
    let points: Float64Array;
    if ('pattern' in request) points = patternPoints(request.pattern, request.segments, request.size_mm, origin);
    else if (request.axes === axes) points = request.points;
    else {
      this.host.log('error', 'JOB_INVALID', `the job has ${request.axes} axes per point but this machine has ${axes} (${maxl.config.motionAxes.join(', ')})`);
      return;
    }
    const count = Math.floor(points.length / axes);
    const bad = points.findIndex((v) => !Number.isFinite(v));
    if (bad >= 0) {
      this.host.log('error', 'JOB_INVALID', `“${request.name}”: point ${Math.floor(bad / axes) + 1} has a coordinate that is not a finite number (${points[bad]}); nothing was started.`);
      return;
    }
    const outside = firstOutside(points, axes, maxl.config.softMin, maxl.config.softMax);
    if (outside >= 0) {
      const p = Array.from(points.subarray(outside * axes, outside * axes + axes), (v) => v.toFixed(2)).join(', ');
      this.host.log('error', 'SOFT_LIMIT', `“${request.name}” leaves the soft limits at point ${outside + 1} (${p} mm). Set the origin elsewhere, use a smaller job, or widen the soft limits in Configure → Axes.`);
      return;
    }
    const start = maxl.nextMoveStart;
    const maxVelocity = request.maxVelocity;
    this.begin(
      {
        name: request.name,
        maxl,
        movesFrom: (i) => {
          const moves: Move[] = [];
          for (let k = i; k < Math.min(count, i + POINTS_RUN); k++) moves.push({ endPosition: Array.from(points.subarray(k * axes, k * axes + axes)), maxVelocity });
          return { moves, at: 0 };
        },
        describeMove: (i) => `point ${i + 1}`,
        count,
        maxVelocity,
        planned_s: 0,
        totalLength: pathLength(start, points, axes),
      },
      previewVertices(start, points, axes),
      `${count.toLocaleString('en')} segments`,
    );
  }

  /**
   * Starts a tool's job. Every linear move is checked against the soft limits
   * first: a job that leaves them does not start at all. False if it did not start.
   */
  startMoves(job: MoveJob, maxl: Maxl): boolean {
    if (this.active) {
      this.host.log('warning', 'JOB_BUSY', `“${this.run?.name}” is still running: cancel it first, or wait until it ends.`);
      return false;
    }
    const start = maxl.nextMoveStart;
    const path = resolvePath(job.moves, maxl.config.motionAxes, start);
    if (typeof path === 'string') {
      this.host.log('error', 'JOB_INVALID', `“${job.name}”: ${path}`);
      return false;
    }
    const axes = start.length;
    const outside = firstOutside(path, axes, maxl.config.softMin, maxl.config.softMax);
    if (outside >= 0) {
      const p = Array.from(path.subarray(outside * axes, outside * axes + axes), (v) => v.toFixed(2)).join(', ');
      this.host.log('error', 'SOFT_LIMIT', `“${job.name}” leaves the soft limits at ${p} mm: fit it to the bed, or move it.`);
      return false;
    }
    const linear = job.moves.filter((m) => !isDwell(m)).length;
    let fastest = 0;
    for (const m of job.moves) if (!isDwell(m) && m.maxVelocity !== undefined) fastest = Math.max(fastest, m.maxVelocity);
    this.begin(
      {
        name: job.name,
        maxl,
        movesFrom: (i) => ({ moves: job.moves, at: i }),
        describeMove: (i) => job.describeMove?.(i) ?? null,
        count: job.moves.length,
        maxVelocity: fastest || Infinity,
        planned_s: job.planned_s ?? 0,
        totalLength: pathLength(start, path, axes),
      },
      previewVertices(start, path, axes),
      `${linear.toLocaleString('en')} moves${job.planned_s ? `, ${job.planned_s.toFixed(1)} s planned` : ''}`,
    );
    return true;
  }

  private begin(
    r: Pick<Run, 'name' | 'maxl' | 'movesFrom' | 'describeMove' | 'count' | 'maxVelocity' | 'planned_s' | 'totalLength'>,
    preview: Float32Array,
    summary: string,
  ): void {
    this.run = {
      ...r,
      phase: 'loading',
      resumable: false,
      stopped: false,
      abort: new AbortController(),
      wake: null,
      fed: 0,
      firstMoveId: 0,
      lastDoneMoveId: 0,
      doneLength: 0,
      motion_s: 0,
    };
    this.host.preview(r.name, preview, preview.length / 3 - 1);
    this.host.log('info', 'JOB', `“${r.name}”: ${summary}, ${r.totalLength.toFixed(0)} mm.`);
    const run = this.run;
    run.phase = 'running';
    void this.feed(run).catch((err) => {
      if (!(err instanceof MaxlError && err.code === 'ABORTED')) this.fail(run, err);
    });
  }

  pause(): void {
    const r = this.run;
    if (!r || r.phase !== 'running') return;
    r.phase = 'pausing';
    r.maxl.pause().then(
      () => {
        if (r.phase === 'pausing') r.phase = 'paused';
      },
      (err) => this.fail(r, err),
    );
  }

  resume(): void {
    const r = this.run;
    if (!r || (r.phase !== 'paused' && r.phase !== 'pausing')) return;
    r.maxl.resume();
    r.phase = 'running';
    r.wake?.();
  }

  cancel(): void {
    const r = this.run;
    if (!r || !this.active) return;
    this.stop(r);
    r.phase = 'cancelling';
    r.maxl.cancel().then(
      () => {
        if (r.phase === 'cancelling') r.phase = 'cancelled';
        this.host.log('info', 'JOB', `“${r.name}” cancelled after ${this.progress()?.doneSegments ?? 0} segments; the machine rests on the path.`);
      },
      (err) => this.fail(r, err),
    );
  }

  /** STOP was pressed: the job stops here (Resume takes it on from there, after reconnecting). */
  halted(): void {
    const r = this.run;
    if (!r || !this.active) return;
    this.stop(r);
    r.phase = 'halted';
    r.resumable = true;
  }

  /**
   * The machine can no longer run the job (a device was lost, the runtime was
   * replaced). `resumable`: it stopped on its path, and the same author can take the
   * rest on after reconnecting (resumeAfterStop).
   */
  abort(reason: string, resumable = false): void {
    const r = this.run;
    if (!r || !this.active) return;
    this.stop(r);
    r.phase = 'failed';
    r.resumable = resumable;
    this.host.log('error', 'JOB_FAILED', `“${r.name}” stopped: ${reason}${resumable ? '. Press Resume to go on from where it stopped.' : ''}`);
  }

  /** Whether the last job stopped off its plan and can be resumed. */
  get resumable(): boolean {
    return this.run?.resumable === true && !this.active;
  }

  /**
   * After maxl.reconnect() and maxl.resumeJob(): the job runs on, its queued rest
   * first, then the moves not fed yet. Returns the job's name, or null if none can.
   */
  resumeAfterStop(): string | null {
    const r = this.run;
    if (!r || !this.resumable) return null;
    r.resumable = false;
    r.stopped = false;
    r.phase = 'running';
    r.abort = new AbortController();
    void this.feed(r).catch((err) => {
      if (!(err instanceof MaxlError && err.code === 'ABORTED')) this.fail(r, err);
    });
    return r.name;
  }

  /** The resumable job will not be resumed (Re-arm started a new author). */
  dropResumable(): void {
    if (this.run) this.run.resumable = false;
  }

  /** Forgets the last job (another machine was chosen: its progress means nothing there). */
  forget(): void {
    if (this.active) this.abort('the machine was changed');
    this.run = null;
  }

  /** A segment finished (from the snapshot builder). */
  onHistorical(seg: SegmentView): void {
    const r = this.run;
    if (!r || r.firstMoveId === 0 || seg.moveId < r.firstMoveId) return;
    r.doneLength += seg.length;
    r.motion_s += seg.duration_s;
    if (seg.moveId > r.lastDoneMoveId) r.lastDoneMoveId = seg.moveId;
  }

  /**
   * Feeds the moves in order, then waits for the machine to finish them. Each step
   * awaits one move (the first, whose receipt gives the job's first move id, or one
   * that finds the queue full and waits for room), then appends the moves that fit
   * now in one synchronous run (addSegmentsNow). A stop aborts both waits.
   */
  private async feed(r: Run): Promise<void> {
    const { maxl } = r;
    const { signal } = r.abort;
    let sliceStart = performance.now();
    // From the first move not fed yet (0, or after a resume).
    while (r.fed < r.count) {
      const i = r.fed;
      const { moves, at } = r.movesFrom(i);
      let receipt;
      try {
        receipt = await maxl.addSegmentToQueue(moves[at], { signal });
      } catch (err) {
        throw this.inJobWords(r, err, i, at);
      }
      if (i === 0) r.firstMoveId = receipt.moveId;
      r.fed = i + 1;
      // A run moves[at + 1 …] as far as there is room; it stops (what fits is queued) at a bad move.
      try {
        r.fed = i + maxl.addSegmentsNow(moves, at + 1) - at;
      } catch (err) {
        const item = err instanceof MaxlError ? batchItemOf(err) : null;
        if (item) r.fed = i + item.index - at;
        throw this.inJobWords(r, err, i, at);
      }
      // Runs are queued without a turn of the event loop: let commands in now and then.
      if (performance.now() - sliceStart > FEED_SLICE_MS) {
        await yieldToEvents();
        sliceStart = performance.now();
        if (signal.aborted) return;
      }
    }
    await this.finished(r);
    if (r.phase !== 'running') return;
    r.phase = 'done';
    this.host.log('info', 'JOB', `“${r.name}” done: ${r.count.toLocaleString('en')} segments in ${r.motion_s.toFixed(1)} s of motion.`);
  }

  /**
   * Resolves once everything fed has run. The machine is also idle while a pause
   * holds it at rest, so a paused run waits for resume() and then for idle again.
   */
  private async finished(r: Run): Promise<void> {
    const { signal } = r.abort;
    for (;;) {
      await r.maxl.whenIdle({ signal });
      if (r.phase !== 'paused' && r.phase !== 'pausing') return;
      await new Promise<void>((resolve) => {
        r.wake = resolve;
        signal.addEventListener('abort', () => resolve(), { once: true });
      });
      r.wake = null;
      if (signal.aborted) return;
    }
  }

  /**
   * A move's error (from the awaited add of the job's move i, which is moves[at], or
   * from a run after it, whose error names its index in `moves`) in the job's words;
   * any other error as it is.
   */
  private inJobWords(r: Run, err: unknown, i: number, at: number): unknown {
    if (!(err instanceof MaxlError) || !isMoveError(err)) return err;
    const item = batchItemOf(err);
    const index = item ? i + item.index - at : i;
    return jobMoveError(err, index, r.describeMove(index));
  }

  /** No more moves for this run: the waits for room and for the end give up. */
  private stop(r: Run): void {
    r.stopped = true;
    r.abort.abort();
  }

  private fail(r: Run, err: unknown): void {
    if (r.stopped && r.phase !== 'running') return;
    this.stop(r);
    r.phase = 'failed';
    const words = errorWords(err);
    this.host.log('error', words.code, `“${r.name}” stopped: ${words.message}`);
  }
}

/**
 * The positions a list of moves visits, n × axes (dwells add none), each end made
 * whole from the position before it; or what is wrong, in words.
 */
function resolvePath(moves: readonly Move[], names: readonly string[], start: readonly number[]): Float64Array | string {
  const out: number[] = [];
  let at = [...start];
  for (const m of moves) {
    if (isDwell(m)) continue;
    const end = m.endPosition;
    if (Array.isArray(end)) {
      if (end.length !== names.length) return `a move has ${end.length} positions but the machine has ${names.length} axes`;
      at = [...end];
    } else {
      at = [...at];
      for (const [axis, v] of Object.entries(end)) {
        const a = names.indexOf(axis);
        if (a < 0) return `"${axis}" is not a motion axis (${names.join(', ')})`;
        at[a] = v;
      }
    }
    out.push(...at);
  }
  return Float64Array.from(out);
}

function firstOutside(points: Float64Array, axes: number, min: readonly number[], max: readonly number[]): number {
  for (let i = 0; i < points.length; i++) {
    const a = i % axes;
    if (points[i] < min[a] || points[i] > max[a]) return Math.floor(i / axes);
  }
  return -1;
}

function pathLength(start: readonly number[], points: Float64Array, axes: number): number {
  let total = 0;
  let prev = 0;
  for (let i = 0; i < points.length; i += axes) {
    let d2 = 0;
    for (let a = 0; a < axes; a++) {
      const from = i === 0 ? start[a] : points[prev + a];
      const d = points[i + a] - from;
      d2 += d * d;
    }
    total += Math.sqrt(d2);
    prev = i;
  }
  return total;
}

function previewVertices(start: readonly number[], points: Float64Array, axes: number): Float32Array {
  const n = points.length / axes;
  const out = new Float32Array((n + 1) * 3);
  for (let a = 0; a < Math.min(3, axes); a++) out[a] = start[a];
  for (let i = 0; i < n; i++) {
    for (let a = 0; a < Math.min(3, axes); a++) out[(i + 1) * 3 + a] = points[i * axes + a];
  }
  return out;
}
