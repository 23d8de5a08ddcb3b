/**
 * What a workbench tool (the plotter, light painting, capture) sees of the worker.
 * Each tool lives in app/tools/<name>/ with its components and one worker module
 * that implements `WorkbenchTool`; the `Workbench` only routes commands to it and
 * tells it when the author changes or STOP is pressed.
 *
 * One thing moves the machine at a time: a job, a jog or a tool. A tool `claim`s
 * the machine before it adds moves and `release`s it when it is done.
 */
import type { Maxl, Scheduler } from '../../core/index.ts';
import type { SimulatedMachine } from '../../core/sim/machine.ts';
import type { MoveJob } from './jobRunner.ts';
import type { LogLevel, MachineConfig, MachinePhase, WorkerEvent } from './protocol.ts';

export interface ToolContext {
  /** The author now, or null while none runs. */
  readonly maxl: Maxl | null;
  readonly phase: MachinePhase;
  /** The simulated machine, or null on real boards. */
  readonly sim: SimulatedMachine | null;
  readonly presetId: string | null;
  readonly config: MachineConfig;
  /** Work origin, machine mm per motion axis. */
  readonly origin: readonly number[];
  readonly scheduler: Scheduler;
  /**
   * Whether real boards are being streamed from this thread now: a job, a jog or a
   * tool moves them, or motion sent to them has not run out. Work that holds the
   * thread for long (reading and planning a big file: a second for 20 000 paths)
   * must wait meanwhile, or the stream falls behind and the boards brake to rest.
   * Never on a simulated machine, which runs on this thread's paced clock and waits
   * with it.
   */
  readonly streamingToBoards: boolean;
  /**
   * Takes the machine for `owner`'s motion. False, with a warning in the log that
   * names `what` and the reason, when the machine is not ready, or a job, a jog or
   * another tool moves it. Claiming twice for the same owner is fine.
   */
  claim(owner: string, what: string): boolean;
  /** Gives the machine back (no-op if `owner` does not hold it). */
  release(owner: string): void;
  /**
   * Runs a tool's moves as a job: the job panel shows its progress and ETA, and
   * pauses, resumes and cancels it. False (with the reason in the log) if it did
   * not start: the machine is not ready or busy, or a move leaves the soft limits.
   */
  startJob(job: MoveJob): boolean;
  log(level: LogLevel, code: string, message: string): void;
  post(e: WorkerEvent, transfer?: Transferable[]): void;
}

export interface WorkbenchTool<C> {
  handle(cmd: C): void;
  /**
   * A new author runs (or none: null). Anything the tool had under way on the old
   * one is over: say so in the log and reset.
   */
  authorChanged(maxl: Maxl | null): void;
  /** STOP was pressed: every device halted; drop what waits, and say what was dropped. */
  stopped(): void;
  /** Once per animation frame of the page: post what changed since the last one, if anything. */
  frame(): void;
}
