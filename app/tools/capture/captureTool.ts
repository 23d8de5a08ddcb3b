/**
 * The capture tool in the worker: runs a test motion (core/capture/testMotions.ts) on
 * the author while the runtime captures every sensor the machine has (it subscribes
 * every sensor reader at begin() and fills maxl.captures), then sends the page a
 * self-contained record (buildRecord.ts), kept in IndexedDB from here (captureDb.ts) so the
 * page never clones a long capture on its own thread.
 *
 * It claims the machine for the motion, says how far it is every 200 ms, and stops on
 * Cancel (the author brakes on the path) or STOP (every device halts): either way the
 * samples captured so far are kept and sent, marked as cut short. Nothing is lost in
 * silence: a motion with more segments than the as-planned history keeps is refused
 * before it starts, and a record whose start fell past the history's horizon says so.
 */
import type { Maxl } from '../../../core/index.ts';
import { limitsAlong, planTestMotion, TestMotionError, type PlannedMotion, type TestMotion } from '../../../core/capture/testMotions.ts';
import type { ToolContext, WorkbenchTool } from '../../worker/toolContext.ts';
import type { SpringParameters } from '../../../core/sim/plant/springResponse.ts';
import { buildRecord, type RecordInput } from './buildRecord.ts';
import { recordTransferables, type CaptureCommand, type CaptureEvent, type CaptureRecord } from './protocol.ts';
import { saveCapture } from './captureDb.ts';
import { emptyField, motionErrorWords } from './motionFields.ts';

const OWNER = 'capture';
/** Ringing recorded after the motion ends, µs. */
const SETTLE_US = 300_000;
const PROGRESS_EVERY_MS = 200;

interface Run {
  maxl: Maxl;
  motion: TestMotion;
  planned: PlannedMotion;
  start_us: number;
  firstIndex: Map<string, number>;
  /** why it was cut short (cancel, STOP, a new author), or null */
  cutShort: string | null;
  settling: boolean;
  abort: () => void;
  aborted: Promise<void>;
}

export class CaptureTool implements WorkbenchTool<CaptureCommand> {
  private run: Run | null = null;
  private lastProgress = 0;

  constructor(private readonly ctx: ToolContext) {}

  handle(cmd: CaptureCommand): void {
    if (cmd.type === 'capture-run') void this.start(cmd.motion);
    else if (cmd.type === 'capture-cancel') this.cancel();
  }

  authorChanged(maxl: Maxl | null): void {
    if (this.run && this.run.maxl !== maxl) this.cut('the machine was reconfigured');
  }

  stopped(): void {
    if (this.run) this.cut('STOP was pressed');
  }

  frame(): void {
    const run = this.run;
    if (!run) return;
    const now = Date.now();
    if (now - this.lastProgress < PROGRESS_EVERY_MS) return;
    this.lastProgress = now;
    let samples = 0;
    let lost = 0;
    for (const [key, c] of run.maxl.captures) {
      samples += c.size - (run.firstIndex.get(key) ?? 0);
      lost += c.gaps.filter((g) => g.index > (run.firstIndex.get(key) ?? 0)).reduce((n, g) => n + g.samples, 0);
    }
    this.post({
      tool: 'capture',
      type: 'capture-progress',
      progress: {
        state: run.settling ? 'settling' : 'running',
        description: run.planned.description,
        elapsed_s: (this.ctx.scheduler.now() - run.start_us) / 1e6,
        duration_s: run.planned.duration_s,
        samples,
        lost,
      },
    });
  }

  private post(e: CaptureEvent, transfer?: Transferable[]): void {
    this.ctx.post(e, transfer);
  }

  private fail(message: string): void {
    this.ctx.log('error', 'CAPTURE', message);
    this.post({ tool: 'capture', type: 'capture-failed', message });
  }

  private async start(motion: TestMotion): Promise<void> {
    const maxl = this.ctx.maxl;
    if (this.run) return this.ctx.log('warning', 'CAPTURE_BUSY', 'A capture is running: cancel it first.');
    if (!maxl || this.ctx.phase !== 'ready') return this.fail(`Cannot capture: the machine is ${this.ctx.phase}.`);
    if (maxl.captures.size === 0) return this.fail('Cannot capture: no sensor on this machine has sent samples (it needs a sensor reader, such as the Accelerometer example).');
    const empty = emptyField(motion);
    if (empty) return this.fail(`Cannot capture: ${empty} is empty: type a number.`);
    let planned: PlannedMotion;
    try {
      planned = planTestMotion(motion, limitsAlong(maxl.config, motion.axis), maxl.nextMoveStart);
    } catch (err) {
      return this.fail(`Cannot capture: ${err instanceof TestMotionError ? motionErrorWords(err) : err instanceof Error ? err.message : String(err)}`);
    }
    const history = maxl.history.capacity;
    if (planned.moves.length >= history) {
      return this.fail(
        `Cannot capture: the motion has ${planned.moves.length} moves, but the as-planned history keeps ${history} segments, so the plan for its start would be gone before the end. Sweep faster or over fewer hertz.`,
      );
    }
    if (!this.ctx.claim(OWNER, `capture (${planned.description})`)) return this.post({ tool: 'capture', type: 'capture-failed', message: 'the machine is busy or not ready (see the log)' });
    let abort = () => {};
    const aborted = new Promise<void>((resolve) => (abort = resolve));
    const run: Run = {
      maxl,
      motion,
      planned,
      start_us: this.ctx.scheduler.now(),
      firstIndex: new Map([...maxl.captures].map(([key, c]) => [key, c.size])),
      cutShort: null,
      settling: false,
      abort,
      aborted,
    };
    this.run = run;
    this.lastProgress = 0;
    this.ctx.log('info', 'CAPTURE', `Capture: ${planned.description}, about ${planned.duration_s.toFixed(1)} s.`);
    try {
      for (const move of planned.moves) {
        if (run.cutShort) break;
        await Promise.race([maxl.addSegmentToQueue(move), aborted]);
      }
      if (!run.cutShort) await Promise.race([maxl.whenIdle(), aborted]);
      run.settling = true;
      if (!run.cutShort) await Promise.race([this.ctx.scheduler.sleep(SETTLE_US), aborted]);
    } catch (err) {
      run.cutShort ??= `the motion failed: ${err instanceof Error ? err.message : String(err)}`;
    }
    this.finish(run);
  }

  private finish(run: Run): void {
    if (this.run !== run) return;
    this.run = null;
    this.ctx.release(OWNER);
    const now = this.ctx.scheduler.now();
    const record = buildRecord({
      maxl: run.maxl,
      id: `${new Date().toISOString()}-${Math.random().toString(36).slice(2, 8)}`,
      date: new Date().toISOString(),
      motion: run.motion,
      planned: run.planned,
      machine: this.ctx.presetId ?? 'boards',
      config: this.ctx.config,
      start_us: run.start_us,
      end_us: now,
      firstIndex: run.firstIndex,
      cutShort: run.cutShort,
      warnings: [],
      truth: this.simulatorTruth(run.motion.axis),
    });
    const samples = record.sensors.reduce((n, s) => n + s.author_us.length, 0);
    const lost = record.sensors.reduce((n, s) => n + s.gaps.reduce((m, g) => m + g.samples, 0), 0);
    const peak = record.analysis ? `; spectrum peak ${record.analysis.peak_hz.toFixed(2)} Hz, lag ${record.analysis.lag_ms.toFixed(1)} ms` : '';
    this.ctx.log(
      run.cutShort ? 'warning' : 'info',
      'CAPTURE',
      `Capture ${run.cutShort ? `cut short (${run.cutShort})` : 'done'}: ${samples} samples${lost > 0 ? `, ${lost} lost (shown as gaps)` : ''}${peak}.`,
    );
    void this.keepAndSend(record);
  }

  /** Keeps the record in IndexedDB (here, off the page's thread), then sends it, its arrays transferred. */
  private async keepAndSend(record: CaptureRecord): Promise<void> {
    let notKept: string | null = null;
    if (typeof indexedDB === 'undefined') notKept = 'there is no IndexedDB here';
    else {
      try {
        await saveCapture(record);
      } catch (err) {
        notKept = err instanceof Error ? err.message : String(err);
      }
    }
    this.post({ tool: 'capture', type: 'capture-done', record, notKept }, recordTransferables(record));
  }

  /** The simulated machine's accelerometer and belt, for the record's ground truth (null on real boards). */
  private simulatorTruth(axis: string): RecordInput['truth'] {
    const sim = this.ctx.sim;
    const chip = sim?.plant.accelerometer;
    const plant = sim?.preset.plant;
    if (!sim || !chip || !plant?.accelerometer) return null;
    const spring = plant.spring;
    const params = typeof (spring as SpringParameters).naturalFrequency_hz === 'number' ? (spring as SpringParameters) : (spring as Record<string, SpringParameters>)[axis];
    return params ? { chip, device: plant.accelerometer.device, spring: params } : null;
  }

  private cancel(): void {
    const run = this.run;
    if (!run) return;
    this.cut('cancelled');
    void run.maxl.cancel().catch(() => {});
  }

  private cut(reason: string): void {
    const run = this.run;
    if (!run || run.cutShort) return;
    run.cutShort = reason;
    run.abort();
  }
}
