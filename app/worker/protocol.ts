/**
 * The one typed message interface between the workbench's main thread and the
 * worker that runs the MAXL core (docs/design.md, decision 9).
 *
 *   main → worker   `Command`: what the user asked for (connect, configure, jog, jobs, stop)
 *   worker → main   `WorkerEvent`: the machine's state, log entries, and at most one
 *                   `Snapshot` per animation frame, whose typed arrays are transferred
 *
 * The main thread asks for a snapshot from requestAnimationFrame and asks again only
 * once the last one arrived, so snapshots never queue up and never outpace frames.
 */
import type { CaptureCommand, CaptureEvent } from '../tools/capture/protocol.ts';
import type { MaxlConfig, ReaderKindName, TransformConfig } from '../../core/index.ts';
import type { LightpaintCommand, LightpaintEvent } from '../tools/lightpaint/protocol.ts';
import type { FileCommand, FileEvent } from '../tools/plotter/files/protocol.ts';
import type { PlotterCommand, PlotterEvent } from '../tools/plotter/protocol.ts';
import type { PortApi, PortKey } from './serialPorts.ts';
import type { SerialAccess } from './workerSerial.ts';

// ---------------------------------------------------------------------------
// Shared shapes

/** The simulated machine a first visit opens. */
export const DEFAULT_PRESET = 'lightPainter';

/** A machine configuration as the workbench edits, stores and exports it: plain JSON. */
export type MachineConfig = Omit<MaxlConfig, 'transforms'> & {
  transforms?: Exclude<TransformConfig, { type: 'function' }>[];
};

export type { ReaderKindName };

export interface ReaderView {
  name: string;
  kind: ReaderKindName;
}

/** One device as the device list shows it. */
export interface DeviceView {
  /** Stable id of the connection (not the device's name, which only its hello tells). */
  id: string;
  /** Where it is: "sim:motorOne", "USB 2341:0043". */
  label: string;
  /** The name its firmware reports; '' until it said hello. */
  name: string;
  firmware: string;
  readers: ReaderView[];
  connection: 'connecting' | 'open' | 'lost' | 'closed';
  /** The device's own state from its last status: idle, running, braking, stopped, halted… */
  deviceState: string;
  rtt_us: number;
  syncError_us: number;
  simulated: boolean;
}

export interface PresetView {
  id: string;
  description: string;
}

/** Where the machine stands, as a whole. */
export type MachinePhase =
  | 'empty' //            no device
  | 'connecting' //       opening sessions, syncing clocks
  | 'ready' //            streaming: jogs and jobs run
  | 'not-ready' //        the config or the subscriptions are wrong, or a device was lost (see `problem`)
  | 'stopped' //          a device braked to rest on the path by itself (the stream fell behind: see `problem`)
  | 'halted'; //          STOP was pressed: every device stopped where it was

export interface MachineState {
  phase: MachinePhase;
  /** In words a user can act on, when phase is not-ready or halted. */
  problem: string;
  /** Which preset runs, or null for real boards. */
  presetId: string | null;
  presets: PresetView[];
  config: MachineConfig;
  motionAxes: string[];
  actuatorAxes: string[];
  /** mm, machine coordinates, per motion axis: the work origin. */
  origin: number[];
}

export type MismatchProblem = 'unknown device' | 'unknown reader' | 'wrong kind' | 'unknown track' | 'reader used twice';

/** What is wrong with one subscription, said where the editor draws it. */
export interface SubscriptionProblem {
  subscription: number;
  problem: MismatchProblem;
  message: string;
}

export interface ConfigCheck {
  /** Bumped per check so that the editor shows the answer to its latest edit. */
  requestId: number;
  /** The config error (field and message), if the config as a whole is invalid. */
  error: { field: string; message: string } | null;
  subscriptions: SubscriptionProblem[];
  /** Every track of the config, for the editor's right side. */
  tracks: { name: string; kind: 'position' | 'velocity' | 'acceleration' | 'event'; space?: 'motion' | 'actuator' }[];
}

export type LogLevel = 'info' | 'warning' | 'error';

export interface LogEntry {
  id: number;
  /** ms since the epoch */
  at: number;
  level: LogLevel;
  /** A MaxlError code, or a workbench one. */
  code: string;
  message: string;
}

export type JobPhase = 'loading' | 'running' | 'pausing' | 'paused' | 'cancelling' | 'cancelled' | 'done' | 'failed' | 'halted';

export interface JobProgress {
  name: string;
  phase: JobPhase;
  totalSegments: number;
  /** Segments the machine has finished. */
  doneSegments: number;
  /** mm */
  totalLength: number;
  doneLength: number;
  /** s, or NaN while unknown */
  eta_s: number;
  /** s of motion so far (pauses excluded) */
  elapsed_s: number;
  /** It stopped off its plan (a lost link, a restart, STOP) and Resume can take it on from there. */
  resumable: boolean;
}

/** What one hold-to-jog release measured. */
export interface JogStopReport {
  /** mm/s at release */
  speed: number;
  /** ms from the release (the input event's time) until the plan starts braking */
  brakeLatency_ms: number;
  /** ms from the release until the plan is at rest (braking at the limit included) */
  restLatency_ms: number;
  /** ms the braking itself takes at the acceleration limit */
  braking_ms: number;
  /** ms from the release until the worker had the stop (page → worker message) */
  delivery_ms: number;
  /** ms of motion the streamer kept locked ahead then (2·RTT + margin, plus a slice) */
  lockedAhead_ms: number;
  /** the streamer's lead, ms */
  lead_ms: number;
}

export type JobPattern = 'square' | 'spiral' | 'zigzag';

/** A job: a polyline, given as points or as a pattern the worker draws (so big jobs cost the page nothing). */
export type JobRequest = {
  name: string;
  /** mm/s cap for every move */
  maxVelocity: number;
} & (
  | {
      /** Drawn from the work origin, within size_mm in x and y. */
      pattern: JobPattern;
      segments: number;
      size_mm: number;
    }
  | {
      /** n points × axes, machine mm, row-major. The first move goes from the tool to point 0. */
      points: Float64Array;
      axes: number;
    }
);

// ---------------------------------------------------------------------------
// Snapshots

/** Segment states in `Snapshot.queueStates`, as the view colours them. */
export const QUEUE_UNPLANNED = 0;
export const QUEUE_PLANNED = 1;

export interface Snapshot {
  type: 'snapshot';
  /** The runtime these segments belong to: a new one clears the view's locked path. */
  runtimeId: number;
  /** Author µs now. */
  time_us: number;
  /** The tool by the author's real-time estimate, machine mm per motion axis. */
  position: Float64Array;
  /** mm/s along the path. */
  speed: number;
  syncError_us: number;
  /**
   * Transmitted segments (locked, append-only) since the last snapshot: 2 vertices
   * (x, y, z) each, starting at segment index `lockedFrom`.
   */
  lockedFrom: number;
  locked: Float32Array;
  /** Segments of the locked path that have finished (historical): the first `historical` of it. */
  historical: number;
  /** Untransmitted segments (2 vertices each) and their states, or null when unchanged. */
  queue: Float32Array | null;
  queueStates: Uint8Array | null;
  /** Job moves handed to the queue so far (the job preview is unplanned from there on). */
  jobFed: number;
  job: JobProgress | null;
  /** Every 250 ms or on change; else null. */
  devices: DeviceView[] | null;
  /** Simulator ground truth, if the machine is simulated: step counts per motor. */
  truth: Record<string, number> | null;
}

// ---------------------------------------------------------------------------
// The tools (app/tools/<name>/protocol.ts): each command and event carries `tool`.

/** Every tool's commands. */
export type ToolCommand = PlotterCommand | FileCommand | LightpaintCommand | CaptureCommand;
/** Every tool's events. */
export type ToolEvent = PlotterEvent | FileEvent | LightpaintEvent | CaptureEvent;

// ---------------------------------------------------------------------------
// main → worker

export type Command =
  | ToolCommand
  | { type: 'use-preset'; presetId: string; config?: MachineConfig }
  /** Which serial APIs the worker can reach itself: answered with 'serial-access'. */
  | { type: 'serial-access' }
  /** A port the page was granted: the worker finds it among its own granted ports, opens it and owns its streams. */
  | { type: 'open-port'; api: PortApi; port: PortKey }
  /**
   * The bridge, for browsers whose workers reach no serial port: the page opened
   * the port and transfers its streams (every byte then crosses the page).
   */
  | {
      type: 'add-port';
      label: string;
      readable: ReadableStream<Uint8Array>;
      writable: WritableStream<Uint8Array>;
      /** what the port carries to the board (its UART at the baud it was opened with) */
      bytesPerSecond: number;
      /** µs a byte on the board's UART (a USB–serial bridge), undefined for native USB (app/worker/uartBridges.ts) */
      uartByteTime_us: number | undefined;
    }
  | { type: 'remove-device'; id: string }
  | { type: 'set-config'; config: MachineConfig }
  | { type: 'check-config'; config: MachineConfig; requestId: number }
  | { type: 'jog-step'; delta: number[]; speed: number }
  | { type: 'jog-start'; direction: number[]; speed: number }
  /** `releasedAt`: the input event's time, ms since the epoch. */
  | { type: 'jog-stop'; releasedAt: number }
  | { type: 'set-origin' }
  | { type: 'go-to-origin'; speed: number }
  | { type: 'stop' }
  | { type: 'rearm' }
  | { type: 'job-start'; job: JobRequest }
  | { type: 'job-pause' }
  | { type: 'job-resume' }
  | { type: 'job-cancel' }
  /** After a stop off the plan: reconnect the same author and run the rest of the stopped job. */
  | { type: 'job-recover' }
  | { type: 'frame' };

// ---------------------------------------------------------------------------
// worker → main

export type WorkerEvent =
  | ToolEvent
  | Snapshot
  | { type: 'machine'; state: MachineState }
  | { type: 'config-check'; check: ConfigCheck }
  | { type: 'serial-access'; access: SerialAccess }
  | { type: 'log'; entry: LogEntry }
  | { type: 'jog-stopped'; report: JogStopReport }
  /**
   * A job's whole path, once, for the view: (n + 1) points × 3, machine mm, the
   * tool's start first; and a coarse copy within `tolerance_mm` for the overview,
   * with the index into `points` of each vertex it kept.
   */
  | { type: 'job-preview'; name: string; points: Float32Array; segments: number; coarse: Float32Array; coarseIndex: Uint32Array; tolerance_mm: number };

/** The transferable buffers of an event, for postMessage. */
export function transferablesOf(e: WorkerEvent): Transferable[] {
  if (e.type === 'snapshot') {
    const list: Transferable[] = [e.position.buffer, e.locked.buffer];
    if (e.queue) list.push(e.queue.buffer);
    if (e.queueStates) list.push(e.queueStates.buffer);
    return list as Transferable[];
  }
  if (e.type === 'job-preview') return [e.points.buffer as ArrayBuffer, e.coarse.buffer as ArrayBuffer, e.coarseIndex.buffer as ArrayBuffer];
  return [];
}
