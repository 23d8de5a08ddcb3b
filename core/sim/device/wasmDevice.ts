/**
 * One simulated board: a wasm instance of a firmware example, with a virtual
 * clock, a serial port on a simulated link, and pins wired to the plant.
 *
 * The device is infinitely fast: each loop() runs at one author instant t,
 * and every micros() inside it returns the device clock at t. The device
 * runner (deviceRunner.ts) decides when loops happen:
 *   - every `loopPeriod_us` while the firmware says it is busy (moving, queued
 *     work, a subscribed sensor: the ABI's idle query);
 *   - every `idleTick_us` while it is idle;
 *   - at once when bytes arrive (they are pushed into the firmware's receive
 *     ring first, as the UART interrupt would), then at the loop period while
 *     received bytes may still wait in the ring: the firmware reads at most
 *     `bytesPerLoop` bytes per loop (device_link.cpp BYTES_PER_LOOP), and its
 *     idle query does not look at the ring. If the firmware exports an rx
 *     count (wasmAbi.ts rxPending) the host asks it instead of estimating.
 *
 * Everything the firmware does to the outside world goes through the imports
 * below, stamped with the loop's author time: serial bytes to the link (all
 * bytes of one loop in one write), pins and buses to the DeviceHardware.
 *
 * Busy-waiting: Arduino's delay() spins on micros(), which would never return
 * if time stood still inside a call. So a call that reads micros() more than
 * `busyWaitAfterCalls` times is taken to be waiting, and from then on each
 * micros() read lets `busyWaitStep_us` of CPU time pass: outputs after it
 * carry the later time, and the next loop starts after the call ended. A
 * normal loop reads the clock a few times and stays at one instant.
 */
import { SimError } from '../errors.ts';
import type { DeviceHardware } from './deviceHardware.ts';
import { DeviceClock, type DeviceClockConfig } from './deviceClock.ts';
import { IMPORT_MODULE, ImportName, RX_STAGING_BYTES, resolveExports, type FirmwareExports } from './wasmAbi.ts';
import { WASI_MODULE, wasiImports } from './wasiStubs.ts';

export interface WasmDeviceOptions {
  /** The simulated device's name (for logs and errors; the firmware reports its own in HELLO). */
  name: string;
  clock: DeviceClockConfig;
  hardware: DeviceHardware;
  /** Receives the bytes the firmware writes, with the author time of the loop that wrote them. */
  serialOut: (bytes: Uint8Array, t_us: number) => void;
  /** Loop period while busy, µs (default 20). */
  loopPeriod_us?: number;
  /** Loop period while idle, µs (default 20 000). */
  idleTick_us?: number;
  /** Keep the last N outputs in `outputs` (default 0: counters only). */
  outputLogSize?: number;
  /** Bytes the firmware takes from its receive ring per loop, at most (default 32, as device_link.cpp). */
  bytesPerLoop?: number;
  /** micros() reads in one call before time starts to pass (default 200). */
  busyWaitAfterCalls?: number;
  /** CPU time per micros() read while busy-waiting, µs (default 1). */
  busyWaitStep_us?: number;
}

export type OutputRecord =
  | { t_us: number; kind: 'serial'; bytes: Uint8Array }
  | { t_us: number; kind: 'digital' | 'analog' | 'servo' | 'pinMode'; pin: number; value: number }
  | { t_us: number; kind: 'led'; pin: number; rgb: Uint8Array }
  | { t_us: number; kind: 'i2cWrite'; address: number; bytes: Uint8Array; status: number }
  | { t_us: number; kind: 'i2cRead'; address: number; bytes: Uint8Array | null };

export interface DeviceCounters {
  loops: number;
  loopsWhileIdle: number;
  bytesReceived: number;
  /** Bytes lost because the firmware's receive ring was full (a UART overrun). */
  bytesOverrun: number;
  bytesSent: number;
  digitalWrites: number;
  ledShows: number;
  servoPulses: number;
  i2cTransactions: number;
}

export class WasmDevice {
  readonly clock: DeviceClock;
  readonly loopPeriod_us: number;
  readonly idleTick_us: number;
  readonly counters: DeviceCounters = {
    loops: 0,
    loopsWhileIdle: 0,
    bytesReceived: 0,
    bytesOverrun: 0,
    bytesSent: 0,
    digitalWrites: 0,
    ledShows: 0,
    servoPulses: 0,
    i2cTransactions: 0,
  };
  /** The last `outputLogSize` outputs, oldest first. */
  readonly outputs: OutputRecord[] = [];
  /** What the firmware printed (stdout/stderr through WASI fd_write), if anything. */
  console = '';
  /** Author time of the loop running now, or of the last one. */
  private t_us = 0;
  /** Author time of the next loop. */
  nextLoop_us = 0;
  /** What the firmware's idle query said after the last loop. */
  idle = false;
  /** Received bytes that may still wait in the firmware's ring (an upper bound). */
  private rxBacklog = 0;
  /** micros() reads in the current call, and the CPU time they let pass (busy-waiting). */
  private clockReads = 0;
  private cpu_us = 0;
  private readonly bytesPerLoop: number;
  private readonly busyWaitAfterCalls: number;
  private readonly busyWaitStep_us: number;
  /** Set when the firmware trapped; the device runs no more. */
  crashed: SimError | null = null;
  private readonly exports: FirmwareExports;
  private readonly hardware: DeviceHardware;
  private txChunks: Uint8Array[] = [];
  private readonly logSize: number;

  private constructor(
    readonly options: WasmDeviceOptions,
    instance: WebAssembly.Instance,
  ) {
    this.clock = new DeviceClock(options.clock);
    this.loopPeriod_us = options.loopPeriod_us ?? 20;
    this.idleTick_us = options.idleTick_us ?? 20_000;
    this.hardware = options.hardware;
    this.logSize = options.outputLogSize ?? 0;
    this.bytesPerLoop = options.bytesPerLoop ?? 32;
    this.busyWaitAfterCalls = options.busyWaitAfterCalls ?? 200;
    this.busyWaitStep_us = options.busyWaitStep_us ?? 1;
    this.exports = resolveExports(instance, options.name);
  }

  /** Instantiates `module` with the ABI's imports wired to this device. Call start() next. */
  static async instantiate(module: WebAssembly.Module, options: WasmDeviceOptions): Promise<WasmDevice> {
    let device: WasmDevice | null = null;
    const self = () => {
      if (!device) throw new SimError('WASM_ABI', `${options.name}: the firmware called the simulator before it was instantiated`);
      return device;
    };
    const env = envImports(self);
    const wasi = wasiImports(options.name, () => self().exports.memory, (_fd, text) => (self().console += text));
    const imports: Record<string, Record<string, WebAssembly.ImportValue>> = {};
    for (const imp of WebAssembly.Module.imports(module)) {
      if (imp.kind !== 'function') throw new SimError('WASM_ABI', `${options.name}: unexpected ${imp.kind} import ${imp.module}.${imp.name}`);
      let fn: ((...args: number[]) => number | void) | undefined;
      if (imp.module === IMPORT_MODULE) fn = env[imp.name];
      else if (imp.module === WASI_MODULE) fn = wasi(imp.name);
      if (!fn) throw new SimError('WASM_ABI', `${options.name}: the firmware imports ${imp.module}.${imp.name}, which the simulator does not provide (firmware/WASM_ABI.md)`);
      (imports[imp.module] ??= {})[imp.name] = fn;
    }
    const instance = await WebAssembly.instantiate(module, imports);
    device = new WasmDevice(options, instance);
    return device;
  }

  get name(): string {
    return this.options.name;
  }

  /** Author time of the loop running now, or of the last one. */
  get time_us(): number {
    return this.t_us;
  }

  /** The author time inside the current call: its start plus any busy-wait CPU time. */
  private get now_us(): number {
    return this.t_us + this.cpu_us;
  }

  /**
   * Replaces a NUL-terminated string in the firmware's memory, as if the
   * sketch had been edited and reflashed: two boards running the same example
   * need different device names (`MAXL_Device maxl("motorOne")` → "motorA").
   * The new string must not be longer, and the old one (with its NUL) must
   * occur exactly once in memory.
   * Call before start().
   */
  renameString(from: string, to: string): void {
    if (to.length > from.length) throw new SimError('SIM_CONFIG', `${this.name}: "${to}" is longer than "${from}", which it replaces in the firmware`);
    const memory = new Uint8Array(this.exports.memory.buffer);
    const needle = new TextEncoder().encode(`${from}\0`);
    const found: number[] = [];
    outer: for (let i = memory.indexOf(needle[0]); i >= 0 && i <= memory.length - needle.length; i = memory.indexOf(needle[0], i + 1)) {
      for (let k = 1; k < needle.length; k++) if (memory[i + k] !== needle[k]) continue outer;
      found.push(i);
    }
    if (found.length !== 1) throw new SimError('SIM_CONFIG', `${this.name}: the firmware holds the string "${from}" ${found.length} times, expected once`);
    memory.fill(0, found[0], found[0] + needle.length);
    memory.set(new TextEncoder().encode(to), found[0]);
  }

  /** Runs the static constructors and setup() at author time t; the first loop is due at t. */
  start(t_us: number): void {
    this.t_us = t_us;
    this.call(() => {
      this.exports.initialise?.();
      this.exports.setup();
    });
    this.flushSerial();
    this.nextLoop_us = this.t_us;
  }

  /** Runs the loop that is due (at nextLoop_us) and schedules the next one. */
  step(): void {
    this.runLoop(this.nextLoop_us);
    this.scheduleNext();
  }

  /** Busy: the firmware has work due, or received bytes may be waiting. */
  get busy(): boolean {
    return !this.idle || this.rxBacklog > 0;
  }

  private scheduleNext(): void {
    let wait = this.busy ? this.loopPeriod_us : this.idleTick_us;
    // A firmware that says when it next has work (a delayed PONG) sleeps until then.
    const wake = this.exports.wakeAfter && this.rxBacklog === 0 ? this.exports.wakeAfter() >>> 0 : 0;
    if (wake > 0) wait = Math.min(this.idleTick_us, Math.max(this.loopPeriod_us, wake === 0xffffffff ? this.idleTick_us : wake));
    this.nextLoop_us = this.t_us + wait;
  }

  /**
   * Bytes arrive at author time t (every loop before t has run): they go into
   * the receive ring, then a loop runs at t and another one loop period later.
   */
  receive(bytes: Uint8Array, t_us: number): void {
    if (this.crashed) return;
    this.t_us = t_us;
    const memory = this.exports.memory;
    for (let offset = 0; offset < bytes.length; offset += RX_STAGING_BYTES) {
      const chunk = bytes.subarray(offset, Math.min(bytes.length, offset + RX_STAGING_BYTES));
      const staging = this.call(() => this.exports.rxBuffer()) >>> 0;
      new Uint8Array(memory.buffer, staging, chunk.length).set(chunk);
      const taken = this.call(() => this.exports.rxPush(chunk.length)) >>> 0;
      this.counters.bytesReceived += taken;
      this.counters.bytesOverrun += chunk.length - taken;
      this.rxBacklog += taken;
    }
    this.runLoop(t_us);
    this.scheduleNext();
  }

  private runLoop(t_us: number): void {
    if (this.crashed) return;
    this.t_us = t_us;
    if (!this.busy) this.counters.loopsWhileIdle++;
    this.counters.loops++;
    this.call(() => this.exports.loop());
    this.idle = this.exports.idle ? this.call(() => this.exports.idle!()) !== 0 : false;
    const pending = this.exports.rxPending;
    this.rxBacklog = pending ? this.call(() => pending()) >>> 0 : Math.max(0, this.rxBacklog - this.bytesPerLoop);
    this.flushSerial();
  }

  /** Calls into the firmware; a trap marks the device crashed and is rethrown as DEVICE_TRAP. */
  private call<T>(fn: () => T): T {
    if (this.crashed) throw this.crashed;
    this.clockReads = 0;
    this.cpu_us = 0;
    try {
      return fn();
    } catch (err) {
      if (err instanceof SimError) {
        this.crashed = err;
        throw err;
      }
      this.crashed = new SimError('DEVICE_TRAP', `${this.name}: the firmware trapped at author time ${this.now_us} µs: ${String(err)}`, { cause: err });
      throw this.crashed;
    } finally {
      // The call took the CPU time it busy-waited.
      this.t_us += this.cpu_us;
      this.cpu_us = 0;
    }
  }

  private flushSerial(): void {
    if (this.txChunks.length === 0) return;
    let bytes: Uint8Array;
    if (this.txChunks.length === 1) bytes = this.txChunks[0];
    else {
      bytes = new Uint8Array(this.txChunks.reduce((n, c) => n + c.length, 0));
      let o = 0;
      for (const c of this.txChunks) {
        bytes.set(c, o);
        o += c.length;
      }
    }
    this.txChunks = [];
    this.counters.bytesSent += bytes.length;
    this.log({ t_us: this.t_us, kind: 'serial', bytes });
    this.options.serialOut(bytes, this.t_us);
  }

  private log(record: OutputRecord): void {
    if (this.logSize === 0) return;
    if (this.outputs.length >= this.logSize) this.outputs.shift();
    this.outputs.push(record);
  }

  /** Bytes of the firmware's memory at [ptr, ptr + length), copied. */
  private read(ptr: number, length: number): Uint8Array {
    return new Uint8Array(this.exports.memory.buffer, ptr >>> 0, length >>> 0).slice();
  }

  /** @internal the env imports call these */
  readonly io = {
    micros: (): number => {
      if (++this.clockReads > this.busyWaitAfterCalls) this.cpu_us += this.busyWaitStep_us;
      return this.clock.microsAt(this.now_us);
    },
    serialWrite: (ptr: number, length: number): void => {
      this.txChunks.push(this.read(ptr, length));
    },
    pinMode: (pin: number, mode: number): void => {
      this.log({ t_us: this.now_us, kind: 'pinMode', pin, value: mode });
      this.hardware.pinMode(pin, mode, this.now_us);
    },
    digitalWrite: (pin: number, value: number): void => {
      this.counters.digitalWrites++;
      this.log({ t_us: this.now_us, kind: 'digital', pin, value });
      this.hardware.digitalWrite(pin, value, this.now_us);
    },
    digitalRead: (pin: number): number => this.hardware.digitalRead(pin, this.now_us),
    analogWrite: (pin: number, value: number): void => {
      this.log({ t_us: this.now_us, kind: 'analog', pin, value });
      this.hardware.analogWrite(pin, value, this.now_us);
    },
    ledShow: (pin: number, ptr: number, count: number): void => {
      const rgb = this.read(ptr, 3 * count);
      this.counters.ledShows++;
      this.log({ t_us: this.now_us, kind: 'led', pin, rgb });
      this.hardware.ledShow(pin, rgb, this.now_us);
    },
    i2cWrite: (address: number, ptr: number, length: number): number => {
      const bytes = this.read(ptr, length);
      const status = this.hardware.i2cWrite(address, bytes, this.now_us);
      this.counters.i2cTransactions++;
      this.log({ t_us: this.now_us, kind: 'i2cWrite', address, bytes, status });
      return status;
    },
    i2cRead: (address: number, ptr: number, length: number): number => {
      const bytes = this.hardware.i2cRead(address, length >>> 0, this.now_us);
      this.counters.i2cTransactions++;
      this.log({ t_us: this.now_us, kind: 'i2cRead', address, bytes });
      if (!bytes) return 0;
      new Uint8Array(this.exports.memory.buffer, ptr >>> 0, bytes.length).set(bytes);
      return bytes.length;
    },
    servoPulse: (pin: number, pulse: number): void => {
      this.counters.servoPulses++;
      this.log({ t_us: this.now_us, kind: 'servo', pin, value: pulse });
      this.hardware.servoPulse(pin, pulse, this.now_us);
    },
  };
}

/** The "env" imports by ABI name, forwarding to a device's io. */
function envImports(self: () => WasmDevice): Record<string, (...args: number[]) => number | void> {
  return {
    [ImportName.micros]: () => self().io.micros(),
    [ImportName.serialWrite]: (ptr, length) => self().io.serialWrite(ptr, length),
    [ImportName.pinMode]: (pin, mode) => self().io.pinMode(pin, mode),
    [ImportName.digitalWrite]: (pin, value) => self().io.digitalWrite(pin, value),
    [ImportName.digitalRead]: (pin) => self().io.digitalRead(pin),
    [ImportName.analogWrite]: (pin, value) => self().io.analogWrite(pin, value),
    [ImportName.ledShow]: (pin, ptr, count) => self().io.ledShow(pin, ptr, count),
    [ImportName.i2cWrite]: (address, ptr, length) => self().io.i2cWrite(address, ptr, length),
    [ImportName.i2cRead]: (address, ptr, length) => self().io.i2cRead(address, ptr, length),
    [ImportName.servoPulse]: (pin, pulse) => self().io.servoPulse(pin, pulse),
  };
}
