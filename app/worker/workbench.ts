/**
 * The worker's machine: the configuration, the MAXL author running the devices
 * (MachineDevices: simulated or real ports), jogs and jobs (JogController,
 * JobRunner), the snapshots the page draws (SnapshotBuilder); and the router of
 * the page's commands, tool commands to their tools (tools.ts).
 *
 * A MAXL author is built for one configuration and one set of links, and stops
 * streaming for good after a halt; so whenever the configuration or the devices
 * change, and on Re-arm after STOP, the workbench ends the author and starts a new
 * one where the machine stands. Ports stay open across that (SharedPort).
 */
import { createMAXL, PacedScheduler, RealScheduler, type Maxl, type RuntimeEvent, type Scheduler } from '../../core/index.ts';
import type { SimulatedMachine } from '../../core/sim/machine.ts';
import { checkConfig } from './configCheck.ts';
import { errorWords } from './errorWords.ts';
import { JobRunner } from './jobRunner.ts';
import { JogController, epochNow } from './jogController.ts';
import { MachineDevices } from './machineDevices.ts';
import type { MoveJob } from './jobRunner.ts';
import type {
  Command,
  JobRequest,
  LogLevel,
  MachineConfig,
  MachinePhase,
  MachineState,
  Snapshot,
  ToolCommand,
  WorkerEvent,
} from './protocol.ts';
import { BRIDGED_STREAMER, realBoardStreamer } from './realBoardStreamer.ts';
import type { OpenedPort, PortApi, PortKey, SerialPortLike } from './serialPorts.ts';
import { serialAccess } from './workerSerial.ts';
import { decimate, overviewTolerance } from './previewDecimation.ts';
import { readyNotes, sampleGapNote } from './runtimeNotes.ts';
import { LeadWatch } from './leadWatch.ts';
import { presetConfig, presetViews, truthOf } from './simulatedMachines.ts';
import { SnapshotBuilder } from './snapshotBuilder.ts';
import type { ToolContext, WorkbenchTool } from './toolContext.ts';
import { createTools } from './tools.ts';

/** Clock sync before streaming starts. */
const SYNC_BEFORE_START_US = 2_000_000;

/**
 * The worker's machine, which the tools see as their `ToolContext` (toolContext.ts):
 * the Workbench itself, read-only to them.
 */
export class Workbench implements ToolContext {
  /** Paced virtual time while the machine is simulated, the wall clock for real boards. */
  scheduler: Scheduler = new RealScheduler();
  presetId: string | null = null;
  config: MachineConfig = { motionAxes: ['x', 'y'], limits: { maxVelocity: 100, maxAcceleration: 1000 } };
  maxl: Maxl | null = null;
  phase: MachinePhase = 'empty';
  /** Work origin, machine mm per motion axis. */
  origin: number[] = [0, 0];
  private readonly devices: MachineDevices;
  private runtimeId = 0;
  private problem = '';
  /** The last error the runtime reported, in words: why a device stopped by itself. */
  private lastError = '';
  /** Machine mm where the next author starts. */
  private position: number[] = [0, 0];
  private nextLogId = 1;
  /** Ports open one after another, in the order the page asked (so devices keep that order). */
  private openingPorts: Promise<void> = Promise.resolve();
  /** Restarts run one after another. */
  private restarting: Promise<void> = Promise.resolve();
  /**
   * Machine changes (a simulated machine chosen, a board joining) run one after
   * another; the count names the newest, so that a simulated machine superseded
   * before it started does not start (choosePreset, joinBoard).
   */
  private switching: Promise<void> = Promise.resolve();
  private machineChanges = 0;
  private readonly snapshots = new SnapshotBuilder();
  /** Tells the user when real boards' lead grew because the machine held the worker back. */
  private readonly leadWatch = new LeadWatch();
  private readonly jobs: JobRunner;
  private readonly jog: JogController;
  private readonly tools: Map<string, WorkbenchTool<ToolCommand>>;
  /** The tool that holds the machine for its motion, if any (ToolContext.claim). */
  private toolOwner: string | null = null;

  constructor(readonly post: (e: WorkerEvent, transfer?: Transferable[]) => void) {
    this.devices = new MachineDevices((level, code, message) => this.log(level, code, message));
    this.jobs = new JobRunner({
      log: (level, code, message) => this.log(level, code, message),
      preview: (name, points, segments) => {
        const tolerance_mm = overviewTolerance(points);
        const coarse = decimate(points, tolerance_mm);
        this.post({ type: 'job-preview', name, points, segments, coarse: coarse.vertices, coarseIndex: coarse.index, tolerance_mm });
      },
    });
    this.jog = new JogController({
      warn: (code, message) => this.log('warning', code, message),
      report: (report) => this.post({ type: 'jog-stopped', report }),
    });
    this.snapshots.onHistorical = (seg) => this.jobs.onHistorical(seg);
    this.tools = createTools(this);
  }

  /** The simulated machine, or null on real boards. */
  get sim(): SimulatedMachine | null {
    return this.devices.sim;
  }

  handle(cmd: Command): void {
    if ('tool' in cmd) {
      const toolCmd = cmd as ToolCommand;
      const name = (toolCmd as { tool: string }).tool;
      const tool = this.tools.get(name);
      if (tool) tool.handle(toolCmd);
      else this.log('error', 'WORKER', `There is no tool "${name}".`);
      return;
    }
    switch (cmd.type) {
      case 'frame': {
        const lead = this.maxl && this.leadWatch.check(this.scheduler.now(), this.maxl.lead_us);
        if (lead) this.log(lead.level, lead.code, lead.message);
        this.post(this.snapshot());
        for (const tool of this.tools.values()) tool.frame();
        return;
      }
      case 'use-preset':
        void this.choosePreset(cmd.presetId, cmd.config);
        return;
      case 'serial-access':
        this.post({ type: 'serial-access', access: serialAccess() });
        return;
      case 'open-port': {
        const { api, port } = cmd;
        this.openingPorts = this.openingPorts.then(() => this.openGrantedPort(api, port));
        return;
      }
      case 'add-port':
        this.log(
          'warning',
          'BRIDGE',
          `${cmd.label}: this browser's workers cannot reach serial ports, so its bytes cross the page, and a busy page can hold them back: the machine streams with ${(BRIDGED_STREAMER.leadMargin_us ?? 0) / 1000} ms of margin.`,
        );
        void this.joinBoard({ label: cmd.label, readable: cmd.readable, writable: cmd.writable, bytesPerSecond: cmd.bytesPerSecond, uartByteTime_us: cmd.uartByteTime_us }, null);
        return;
      case 'remove-device':
        void this.removeDevice(cmd.id);
        return;
      case 'set-config': {
        // The page refuses to apply an invalid config; this is the last guard, so a
        // bad config never replaces a good one (nor gets saved).
        const problem = checkConfig(cmd.config, [], 0).error;
        if (problem) {
          this.log('error', 'CONFIG_INVALID', `The configuration was not applied: ${problem.message}`);
          return;
        }
        this.config = cmd.config;
        this.publish();
        void this.restart();
        return;
      }
      case 'check-config':
        this.post({ type: 'config-check', check: checkConfig(cmd.config, this.devices.known(), cmd.requestId) });
        return;
      case 'jog-step':
        if (this.canJog()) this.jog.step(this.maxl as Maxl, cmd.delta, cmd.speed);
        return;
      case 'jog-start':
        if (this.canJog()) this.jog.start(this.maxl as Maxl, cmd.direction, cmd.speed);
        return;
      case 'jog-stop':
        void this.jog.stop(cmd.releasedAt);
        return;
      case 'set-origin':
        if (this.maxl && !this.jobs.active) {
          this.origin = [...this.maxl.nextMoveStart];
          this.log('info', 'ORIGIN', `Origin set at ${this.origin.map((v) => v.toFixed(3)).join(', ')} mm (machine coordinates).`);
          this.publish();
        }
        return;
      case 'go-to-origin':
        if (this.canJog()) this.jog.moveTo(this.maxl as Maxl, this.origin, cmd.speed);
        return;
      case 'stop':
        void this.stop();
        return;
      case 'rearm':
        void this.restart();
        return;
      case 'job-start':
        this.startJobRequest(cmd.job);
        return;
      case 'job-pause':
        this.jobs.pause();
        return;
      case 'job-resume':
        this.jobs.resume();
        return;
      case 'job-cancel':
        this.jobs.cancel();
        return;
      case 'job-recover':
        void this.recoverJob();
        return;
    }
  }

  // --- devices ---

  /**
   * A simulated machine chosen from the menu. Choices run one after another, and a
   * newer one supersedes an older one that has not finished starting: a machine
   * still connecting stops at once (its author ends, and begin() rejects), so a
   * choice made while the page opens on the default machine does not wait out that
   * machine's clock sync, nor run beside it.
   */
  private choosePreset(id: string, config?: MachineConfig): Promise<void> {
    const choice = this.newMachineChange();
    this.switching = this.switching.then(() => (choice === this.machineChanges ? this.usePreset(id, config, choice) : undefined));
    return this.switching;
  }

  /**
   * A board joins (its port opened), after the machine changes before it, and
   * superseding a simulated machine chosen but not started yet: so a board granted
   * while the page still starts its default machine replaces that machine, as it
   * does once the machine is ready, rather than running beside it. Boards are never
   * superseded: each one added joins.
   */
  private joinBoard(link: OpenedPort, serialPort: SerialPortLike | null): Promise<void> {
    this.newMachineChange();
    this.switching = this.switching.then(() => this.addPort(link, serialPort));
    return this.switching;
  }

  /** Counts a new machine change, and stops a machine still connecting at once (its begin() rejects), so the change need not wait out its clock sync. */
  private newMachineChange(): number {
    if (this.phase === 'connecting') void this.endAuthor();
    return ++this.machineChanges;
  }

  private async usePreset(id: string, config: MachineConfig | undefined, choice: number): Promise<void> {
    let base: MachineConfig;
    try {
      base = presetConfig(id);
    } catch (err) {
      this.log('error', 'PRESET', errorWords(err).message);
      return;
    }
    await this.closeDevices();
    if (choice !== this.machineChanges) return;
    this.useScheduler(new PacedScheduler());
    this.presetId = id;
    this.config = config ?? base;
    this.origin = new Array<number>(this.config.motionAxes.length).fill(0);
    this.position = [...this.origin];
    this.phase = 'connecting';
    this.problem = '';
    this.publish();
    try {
      await this.devices.startSimulated(id, this.scheduler);
    } catch (err) {
      const words = errorWords(err);
      this.phase = 'not-ready';
      this.problem = `The simulated machine could not start: ${words.message}`;
      this.log('error', words.code, this.problem);
      this.publish();
      return;
    }
    // Superseded while it started: the next choice closes it.
    if (choice !== this.machineChanges) return;
    await this.restart();
  }

  private async openGrantedPort(api: PortApi, key: PortKey): Promise<void> {
    const opened = await this.devices.openGranted(api, key);
    if (opened) await this.joinBoard(opened.link, opened.serialPort);
  }

  private async addPort(link: OpenedPort, serialPort: SerialPortLike | null): Promise<void> {
    if (this.devices.sim) {
      // A real board joins: the simulated machine goes, the configuration stays for editing.
      await this.closeDevices();
      this.presetId = null;
      this.log('info', 'CONNECT', 'Left the simulated machine for real boards; the configuration is kept: check its subscriptions.');
    }
    if (this.scheduler instanceof PacedScheduler) this.useScheduler(new RealScheduler());
    this.devices.addPort(link, serialPort);
    await this.restart();
  }

  private async removeDevice(id: string): Promise<void> {
    if (!this.devices.removable(id)) return;
    await this.endAuthor();
    await this.devices.remove(id);
    await this.restart();
  }

  private async closeDevices(): Promise<void> {
    await this.endAuthor();
    this.jobs.forget();
    await this.devices.closeAll();
  }

  /** Swaps the time base; only between machines, when nothing runs on the old one. */
  private useScheduler(next: Scheduler): void {
    if (this.scheduler instanceof PacedScheduler) this.scheduler.stop();
    this.scheduler = next;
  }

  // --- the author ---

  /** Ends the current author (if any) and starts one for the current config and devices. */
  restart(): Promise<void> {
    this.restarting = this.restarting.then(() => this.doRestart());
    return this.restarting;
  }

  private async doRestart(): Promise<void> {
    await this.endAuthor();
    if (this.devices.count === 0) {
      this.setPhase('empty', 'No device: add one, or choose a simulated machine.');
      return;
    }
    const runtimeId = ++this.runtimeId;
    this.lastError = '';
    this.setPhase('connecting', '');
    const axes = this.config.motionAxes?.length ?? 0;
    if (this.position.length !== axes) this.position = new Array<number>(axes).fill(0);
    if (this.origin.length !== axes) this.origin = new Array<number>(axes).fill(0);
    // Simulated machines run on paced virtual time, where every timer fires on time
    // and no byte waits on a browser: the core's default margins. Real boards run
    // on the wall clock: margins for their links (realBoardStreamer.ts).
    const streamer = this.scheduler instanceof PacedScheduler ? undefined : realBoardStreamer(this.devices.linkKinds());
    let maxl: Maxl;
    try {
      // Real boards: a dry move first (core/net/warmUp.ts), so the first jog's pump runs warm code.
      maxl = createMAXL(this.config, { links: this.devices.sessions(), initialPosition: this.position, scheduler: this.scheduler, streamer, syncBeforeStart_us: SYNC_BEFORE_START_US, warmUp: streamer !== undefined });
    } catch (err) {
      const words = errorWords(err);
      this.setPhase('not-ready', words.message);
      this.log('error', words.code, words.message);
      return;
    }
    this.maxl = maxl;
    this.snapshots.attach(maxl);
    for (const tool of this.tools.values()) tool.authorChanged(maxl);
    maxl.on((e) => this.onRuntime(e, runtimeId));
    try {
      await maxl.begin();
      if (runtimeId !== this.runtimeId) return;
      this.devices.learn(maxl);
      this.setPhase('ready', '');
      this.log('info', 'READY', `Ready: ${this.devices.known().map((d) => d.name).join(', ')} in sync.`);
      for (const n of readyNotes(streamer ?? null, maxl.lead_us, maxl.feedLimit)) this.log(n.level, n.code, n.message);
      this.leadWatch.ready(streamer ? maxl.lead_us : NaN);
    } catch (err) {
      if (runtimeId !== this.runtimeId) return;
      this.devices.learn(maxl);
      const words = errorWords(err);
      this.log('error', words.code, words.message);
      await this.endAuthor();
      this.setPhase('not-ready', words.message);
    }
  }

  private async endAuthor(): Promise<void> {
    const maxl = this.maxl;
    if (!maxl) return;
    this.maxl = null;
    this.jobs.abort('the machine was reconfigured');
    this.jobs.dropResumable();
    this.jog.reset();
    this.toolOwner = null;
    for (const tool of this.tools.values()) tool.authorChanged(null);
    this.snapshots.attach(null);
    // After STOP or a lost link the devices report where they stopped ('stopped'); otherwise the plan knows.
    if (this.phase === 'ready') this.position = [...maxl.estimate().position];
    this.runtimeId++;
    await maxl.end();
  }

  private onRuntime(e: RuntimeEvent, runtimeId: number): void {
    if (runtimeId !== this.runtimeId) return;
    if (e.type === 'error') {
      const words = errorWords(e.error);
      this.lastError = words.message;
      this.log('error', words.code, words.message);
    } else if (e.type === 'streamStopped') {
      // The machine rests on the path with nothing more to run, even if no device reports a stop.
      this.stoppedByItself(e.what);
    } else if (e.type === 'device') {
      this.devices.touch();
      if (e.state === 'lost' || e.state === 'rebooted') {
        this.jobs.abort(`${e.device} was lost`, true);
        this.jog.reset();
        if (this.phase === 'ready') this.setPhase('not-ready', `${e.device}: ${e.reason ?? e.state}. The machine brakes to rest on the path. Check the cable and power, then press Re-arm.`);
      }
    } else if (e.type === 'sampleGap') {
      const n = sampleGapNote(e.device, e.reader, e.gap);
      this.log(n.level, n.code, n.message);
    } else if (e.type === 'stopped') {
      if (e.position) this.position = [...e.position];
      // A device braked to rest by itself (STOP sets 'halted' first): this author
      // cannot stream on from there, so the machine waits for Re-arm.
      this.stoppedByItself(`${e.device} braked to rest on the path`);
    }
  }

  /**
   * The stream stopped without STOP (a device braked, or refused a segment): this
   * author cannot go on from there, so the job ends and the machine waits for Re-arm.
   */
  private stoppedByItself(what: string): void {
    if (this.phase !== 'ready') return;
    this.jobs.abort(what, this.maxl?.stopped != null);
    this.jog.reset();
    this.toolOwner = null;
    for (const tool of this.tools.values()) tool.stopped();
    const why = this.lastError ? ` (${this.lastError})` : '';
    this.setPhase('stopped', `${what[0].toUpperCase()}${what.slice(1)}${why}. Press Re-arm to continue from where it stopped.`);
  }

  private canJog(): boolean {
    if (!this.maxl || this.phase !== 'ready') {
      this.log('warning', 'NOT_READY', `Cannot jog: the machine is ${this.phase}${this.problem ? ` (${this.problem.split('\n')[0]})` : ''}.`);
      return false;
    }
    if (this.jobs.active) {
      this.log('warning', 'JOB_BUSY', 'Cannot jog while a job runs: pause or cancel it first.');
      return false;
    }
    if (this.toolOwner) {
      this.log('warning', 'TOOL_BUSY', `Cannot jog while the ${this.toolOwner} tool moves the machine.`);
      return false;
    }
    return true;
  }

  /** ToolContext.claim: takes the machine for `owner`'s motion, or says in the log why not. */
  claim(owner: string, what: string): boolean {
    let why = '';
    if (!this.maxl || this.phase !== 'ready') why = `the machine is ${this.phase}${this.problem ? ` (${this.problem.split('\n')[0]})` : ''}`;
    else if (this.jobs.active) why = 'a job runs: pause or cancel it first';
    else if (this.jog.isHolding) why = 'a jog is held';
    else if (this.toolOwner && this.toolOwner !== owner) why = `the ${this.toolOwner} tool moves the machine`;
    if (why) {
      this.log('warning', this.phase === 'ready' ? 'MACHINE_BUSY' : 'NOT_READY', `Cannot ${what}: ${why}.`);
      return false;
    }
    this.toolOwner = owner;
    return true;
  }

  /** ToolContext.streamingToBoards. */
  get streamingToBoards(): boolean {
    const maxl = this.maxl;
    if (this.devices.sim || !maxl || this.phase !== 'ready') return false;
    if (this.jobs.active || this.jog.isHolding || this.toolOwner !== null) return true;
    return maxl.queue.untransmittedCount > 0 || maxl.queue.transmittedEnd_us > this.scheduler.now();
  }

  /** ToolContext.release. */
  release(owner: string): void {
    if (this.toolOwner === owner) this.toolOwner = null;
  }

  /** ToolContext.startJob: a tool's moves as a job. */
  startJob(job: MoveJob): boolean {
    if (!this.claim('job', `start “${job.name}”`)) return false;
    this.toolOwner = null;
    return this.jobs.startMoves(job, this.maxl as Maxl);
  }

  private startJobRequest(request: JobRequest): void {
    if (!this.maxl || this.phase !== 'ready') {
      this.log('warning', 'NOT_READY', `Cannot start “${request.name}”: the machine is ${this.phase}.`);
      return;
    }
    if (this.jog.isHolding) return;
    if (this.toolOwner) {
      this.log('warning', 'TOOL_BUSY', `Cannot start “${request.name}” while the ${this.toolOwner} tool moves the machine.`);
      return;
    }
    this.jobs.start(request, this.maxl, this.origin);
  }

  /**
   * Resume after a stop off the plan (a lost link, a restarted board, STOP): the
   * same author reconnects to every device (fresh sessions on the same ports), each
   * board says where it stopped, clocks re-sync, and the rest of the job runs from
   * there (core: maxl.reconnect(), maxl.resumeJob()). Re-arm instead drops the job.
   */
  private async recoverJob(): Promise<void> {
    const maxl = this.maxl;
    if (!maxl || !maxl.stopped || !this.jobs.resumable) {
      this.log('warning', 'NOTHING_TO_RESUME', 'Nothing to resume: no job stopped off its path. Start a job, or press Re-arm.');
      return;
    }
    const runtimeId = this.runtimeId;
    this.setPhase('connecting', 'Reconnecting to resume the job…');
    try {
      const report = await maxl.reconnect(this.devices.sessions());
      if (runtimeId !== this.runtimeId) return;
      this.devices.learn(maxl);
      maxl.resumeJob();
      const name = this.jobs.resumeAfterStop();
      this.lastError = '';
      this.setPhase('ready', '');
      const from = report.resumeFrom ? ` from ${report.resumeFrom.map((v) => v.toFixed(3)).join(', ')} mm` : '';
      const estimated = report.boards.some((b) => b.source === 'estimate') ? ' (a restarted board’s position is estimated from the plan: home the machine if exactness matters)' : '';
      this.log('info', 'RESUMED', `Resumed “${name}”${from}: ${report.remaining} segments left${estimated}.`);
    } catch (err) {
      if (runtimeId !== this.runtimeId) return;
      const words = errorWords(err);
      this.log('error', words.code, words.message);
      this.setPhase('stopped', `${words.message}\nPress Resume to try again, or Re-arm to drop the job.`);
    }
  }

  /** STOP: every device stops where it is, now. */
  private async stop(): Promise<void> {
    const maxl = this.maxl;
    this.jog.reset();
    this.jobs.halted();
    this.toolOwner = null;
    for (const tool of this.tools.values()) tool.stopped();
    if (!maxl || this.phase !== 'ready') {
      this.log('warning', 'STOP', 'STOP: nothing was streaming.');
      return;
    }
    this.position = [...maxl.estimate().position];
    this.setPhase('halted', 'STOP pressed: every device stopped where it was. Press Re-arm to continue from there.');
    this.log('warning', 'STOP', 'STOP: HALT sent to every device.');
    try {
      await maxl.halt();
    } catch (err) {
      const words = errorWords(err);
      this.log('error', words.code, words.message);
    }
  }

  // --- to the page ---

  private setPhase(phase: MachinePhase, problem: string): void {
    this.phase = phase;
    this.problem = problem;
    this.publish();
  }

  private publish(): void {
    const state: MachineState = {
      phase: this.phase,
      problem: this.problem,
      presetId: this.presetId,
      presets: presetViews(),
      config: this.config,
      motionAxes: this.config.motionAxes ?? [],
      actuatorAxes: (this.config.transforms ?? []).flatMap((t) => t.to),
      origin: this.origin,
    };
    this.post({ type: 'machine', state });
  }

  log(level: LogLevel, code: string, message: string): void {
    this.post({ type: 'log', entry: { id: this.nextLogId++, at: Date.now(), level, code, message } });
  }

  private snapshot(): Snapshot {
    const maxl = this.maxl;
    const axes = this.config.motionAxes?.length ?? 0;
    const estimate = maxl?.estimate();
    const position = new Float64Array(axes);
    const at = estimate?.position ?? this.position;
    for (let i = 0; i < axes; i++) position[i] = at[i] ?? 0;
    const locked = this.snapshots.takeLocked();
    const queue = this.snapshots.takeQueue();
    const now = epochNow();
    const devices = this.devices.viewsIfDue(maxl, now);
    return {
      type: 'snapshot',
      runtimeId: this.runtimeId,
      time_us: this.scheduler.now(),
      position,
      speed: estimate?.speed ?? 0,
      syncError_us: estimate?.syncError_us ?? NaN,
      lockedFrom: locked.from,
      locked: locked.vertices,
      historical: this.snapshots.historicalCount,
      queue: queue.vertices,
      queueStates: queue.states,
      jobFed: this.jobs.fed,
      job: this.jobs.progress(),
      devices,
      truth: this.devices.sim ? truthOf(this.devices.sim) : null,
    };
  }
}
