/**
 * The page's state: what the worker last said, as Svelte 5 runes, and the
 * commands the components send. Big typed arrays (snapshots' paths, job
 * previews) go straight to the 3D view and never become reactive state.
 */
import { WorkerClient } from './workerClient.ts';
import { BOARDS, lastMachine, saveConfig, savedConfig } from './configStorage.ts';
import { configProblems } from './configProblems.ts';
import { connectErrorWords, openPort, portKey, serialSupport, type PortApi, type SerialPortLike, type SerialSupport } from './serialConnect.ts';
import type { SerialAccess } from '../worker/workerSerial.ts';
import {
  DEFAULT_PRESET,
  type Command,
  type ConfigCheck,
  type DeviceView,
  type JobProgress,
  type JobRequest,
  type JogStopReport,
  type LogEntry,
  type LogLevel,
  type MachineConfig,
  type MachineState,
  type Snapshot,
} from '../worker/protocol.ts';

/** Log entries kept on the page. */
const LOG_LIMIT = 500;

export interface PreviewData {
  points: Float32Array;
  coarse: Float32Array;
  coarseIndex: Uint32Array;
  tolerance_mm: number;
}

export interface ViewSink {
  applySnapshot(s: Snapshot): void;
  setPreview(preview: PreviewData): void;
}

export class WorkbenchStore {
  readonly client = new WorkerClient();
  machine = $state.raw<MachineState | null>(null);
  devices = $state.raw<DeviceView[]>([]);
  log = $state.raw<LogEntry[]>([]);
  job = $state.raw<JobProgress | null>(null);
  position = $state.raw<number[]>([]);
  speed = $state(0);
  syncError_us = $state(NaN);
  jogReport = $state.raw<JogStopReport | null>(null);
  check = $state.raw<ConfigCheck | null>(null);
  truth = $state.raw<Record<string, number> | null>(null);
  serial = $state.raw<SerialSupport | null>(null);
  previewSegments = $state(0);
  /** The 3D view, once mounted; previews that arrive before it wait. */
  private view: ViewSink | null = null;
  private pendingPreview: PreviewData | null = null;
  private nextCheck = 1;
  private localLogId = -1;
  /** Which serial APIs the worker reaches itself (its answer to 'serial-access'). */
  private readonly workerAccess: Promise<SerialAccess>;

  constructor() {
    this.workerAccess = new Promise((resolve) => {
      const off = this.client.on((e) => {
        if (e.type !== 'serial-access') return;
        off();
        resolve(e.access);
      });
    });
    this.send({ type: 'serial-access' });
    this.client.on((e) => {
      switch (e.type) {
        case 'snapshot':
          this.onSnapshot(e);
          break;
        case 'machine':
          this.machine = e.state;
          saveConfig(e.state.presetId ?? BOARDS, e.state.config);
          break;
        case 'log':
          this.addLog(e.entry);
          break;
        case 'config-check':
          if (!this.check || e.check.requestId >= this.check.requestId) this.check = e.check;
          break;
        case 'jog-stopped':
          this.jogReport = e.report;
          break;
        case 'job-preview':
          this.previewSegments = e.segments;
          if (this.view) this.view.setPreview(e);
          else this.pendingPreview = e;
          break;
      }
    });
  }

  send(cmd: Command, transfer: Transferable[] = []): void {
    this.client.send(cmd, transfer);
  }

  attachView(view: ViewSink | null): void {
    this.view = view;
    if (view && this.pendingPreview) {
      view.setPreview(this.pendingPreview);
      this.pendingPreview = null;
    }
  }

  /** First load: granted ports reconnect; otherwise the last (or default) simulated machine opens. */
  async start(): Promise<void> {
    this.client.startFrames();
    this.serial = await serialSupport();
    if (this.serial.kind !== 'none') {
      try {
        const ports = await this.serial.api.getPorts();
        if (ports.length > 0) {
          for (const port of ports) await this.connectPort(port);
          return;
        }
      } catch (err) {
        this.note('warning', 'CONNECT', `Could not reconnect granted ports: ${connectErrorWords(err)}`);
      }
    }
    const last = lastMachine();
    this.usePreset(last && last !== BOARDS ? last : DEFAULT_PRESET);
  }

  usePreset(presetId: string, config: MachineConfig | undefined = savedConfig(presetId)): void {
    this.previewSegments = 0;
    const problems = config ? configProblems(config) : [];
    if (problems.length > 0) {
      // Saved by an older version, or edited by hand: never load what Apply would refuse.
      this.note('warning', 'CONFIG', `The saved configuration of ${presetId} is not valid (${problems[0].field}: ${problems[0].message}); using the preset's own.`);
      config = undefined;
    }
    this.send({ type: 'use-preset', presetId, config });
  }

  /** "Add device": the browser's port picker (needs this click), then the worker takes the streams. */
  async addDevice(): Promise<void> {
    const serial = this.serial ?? (this.serial = await serialSupport());
    if (serial.kind === 'none') {
      this.note('error', 'NO_SERIAL', serial.reason);
      return;
    }
    let port: SerialPortLike;
    try {
      port = await serial.api.requestPort();
    } catch (err) {
      this.note('warning', 'CONNECT', connectErrorWords(err));
      return;
    }
    await this.connectPort(port);
  }

  /**
   * The worker opens the port the page was granted, if its own navigator reaches
   * it (Chrome: Web Serial and WebUSB are both in dedicated workers), and owns its
   * streams. Otherwise the bridge: the page opens it and transfers the streams.
   */
  private async connectPort(port: SerialPortLike): Promise<void> {
    const serial = this.serial;
    if (!serial || serial.kind === 'none') return;
    const api: PortApi = serial.kind === 'native' ? 'serial' : 'usb';
    try {
      if ((await this.workerAccess)[api]) {
        this.send({ type: 'open-port', api, port: await portKey(port, serial.api) });
        return;
      }
      const opened = await openPort(port);
      this.send({ type: 'add-port', label: opened.label, readable: opened.readable, writable: opened.writable, bytesPerSecond: opened.bytesPerSecond, uartByteTime_us: opened.uartByteTime_us }, [
        opened.readable as unknown as Transferable,
        opened.writable as unknown as Transferable,
      ]);
    } catch (err) {
      this.note('error', 'CONNECT', connectErrorWords(err));
    }
  }

  checkConfig(config: MachineConfig): void {
    this.send({ type: 'check-config', config: $state.snapshot(config) as MachineConfig, requestId: this.nextCheck++ });
  }

  applyConfig(config: MachineConfig): void {
    this.send({ type: 'set-config', config: $state.snapshot(config) as MachineConfig });
  }

  startJob(job: JobRequest): void {
    this.previewSegments = 0;
    this.send({ type: 'job-start', job }, 'points' in job ? [job.points.buffer as ArrayBuffer] : []);
  }

  stop(): void {
    this.send({ type: 'stop' });
  }

  /** A message from the page itself into the log. */
  note(level: LogLevel, code: string, message: string): void {
    this.addLog({ id: this.localLogId--, at: Date.now(), level, code, message });
  }

  /**
   * Entries arriving together (a refusal from every device, a burst of them) are
   * added in one update per animation frame, so a flood of errors cannot hold up
   * the page.
   */
  private pendingLog: LogEntry[] = [];
  private addLog(entry: LogEntry): void {
    this.pendingLog.push(entry);
    if (this.pendingLog.length > 1) return;
    requestAnimationFrame(() => {
      const next = this.log.concat(this.pendingLog);
      this.pendingLog = [];
      this.log = next.length > LOG_LIMIT ? next.slice(next.length - LOG_LIMIT) : next;
    });
  }

  private onSnapshot(s: Snapshot): void {
    this.view?.applySnapshot(s);
    const p = Array.from(s.position);
    if (p.length !== this.position.length || p.some((v, i) => v !== this.position[i])) this.position = p;
    if (s.speed !== this.speed) this.speed = s.speed;
    if (!Object.is(s.syncError_us, this.syncError_us)) this.syncError_us = s.syncError_us;
    if (s.devices) this.devices = s.devices;
    if (s.job || this.job) this.job = s.job;
    if (s.truth) this.truth = s.truth;
  }
}
