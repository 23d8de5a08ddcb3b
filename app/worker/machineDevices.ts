/**
 * The machine's devices as the worker holds them: the links of a simulated
 * machine, or real boards' serial ports (opened here in the worker, or bridged
 * through the page where workers reach no port), in the order they were added,
 * each with what it said in its last hello.
 *
 * Ports stay open across authors (SharedPort): the Workbench ends its author
 * before it closes or removes one, and starts a new author after.
 */
import type { DeviceInfo, Maxl, Scheduler } from '../../core/index.ts';
import type { SimulatedMachine } from '../../core/sim/machine.ts';
import { errorWords } from './errorWords.ts';
import type { DeviceView, LogLevel } from './protocol.ts';
import type { RealLink } from './realBoardStreamer.ts';
import { SharedPort } from './sharedPort.ts';
import { findGrantedPort, keyLabel, openErrorWords, openPort, portLabel, type OpenedPort, type PortApi, type PortKey, type SerialPortLike } from './serialPorts.ts';
import { startSimulatedMachine } from './simulatedMachines.ts';
import { grantedPorts, watchDisconnects } from './workerSerial.ts';

export interface DeviceConnection {
  id: string;
  port: SharedPort;
  simulated: boolean;
  /** Its bytes cross the page (a port the page opened, for a browser whose workers reach no port). */
  bridged: boolean;
  /** The serial port this worker opened for it, if it did. */
  serialPort: SerialPortLike | null;
  /** What it said in its last hello. */
  info: DeviceInfo | null;
}

/** A port this worker opened, with the serial port behind it. */
export interface GrantedPortOpened {
  link: OpenedPort;
  serialPort: SerialPortLike;
}

/** Device reports go to the page at most this often, ms. */
const DEVICE_REPORT_MS = 250;

type Log = (level: LogLevel, code: string, message: string) => void;

export class MachineDevices {
  private list: DeviceConnection[] = [];
  private simulated: SimulatedMachine | null = null;
  private nextId = 1;
  /** The list or a hello changed since the page last heard: report at the next snapshot. */
  private changed = true;
  private lastReport = 0;
  private watchingDisconnects = false;

  constructor(private readonly log: Log) {}

  /** The simulated machine, or null on real boards. */
  get sim(): SimulatedMachine | null {
    return this.simulated;
  }

  get count(): number {
    return this.list.length;
  }

  /** One link per device, in order, for a new author (`createMAXL`'s `links`). */
  sessions() {
    return this.list.map((d) => d.port.session());
  }

  /** What the real-board streamer needs to know of each link (realBoardStreamer.ts). */
  linkKinds(): RealLink[] {
    return this.list.map((d) => ({ bytesPerSecond: d.port.bytesPerSecond, bridged: d.bridged }));
  }

  /** What the devices said in their hellos (for config checks). */
  known(): DeviceInfo[] {
    return this.list.flatMap((d) => (d.info ? [d.info] : []));
  }

  /** Starts a preset's simulated machine and takes its links as the devices. Throws if it cannot start. */
  async startSimulated(id: string, scheduler: Scheduler): Promise<void> {
    const sim = await startSimulatedMachine(id, scheduler, (err) => this.log('error', 'SIM', `The simulated machine failed: ${errorWords(err).message}`));
    this.simulated = sim;
    for (const [name, link] of Object.entries(sim.links)) {
      this.list.push({ id: `sim-${this.nextId++}`, port: new SharedPort({ ...link, label: link.label ?? `sim:${name}` }), simulated: true, bridged: false, serialPort: null, info: null });
    }
    this.changed = true;
    this.log('info', 'SIM', `Simulated ${id}: ${Object.keys(sim.links).join(', ')}.`);
  }

  /**
   * A port granted to the page: found among this worker's own granted ports and
   * opened here, its streams owned here (no byte crosses the page). Null, with the
   * reason in the log, if it could not be.
   */
  async openGranted(api: PortApi, key: PortKey): Promise<GrantedPortOpened | null> {
    const label = keyLabel(key);
    if (!this.watchingDisconnects) {
      this.watchingDisconnects = true;
      watchDisconnects((port, info) => this.portDisappeared(port, info));
    }
    try {
      const serialPort = await findGrantedPort(await grantedPorts(api), key);
      return { link: await openPort(serialPort), serialPort };
    } catch (err) {
      this.log('error', 'CONNECT', `Could not connect ${label} in the worker: ${openErrorWords(err, label)} Nothing changed: the machine runs as before.`);
      return null;
    }
  }

  /** A real board joins (the caller left any simulated machine first). */
  addPort(link: OpenedPort, serialPort: SerialPortLike | null): void {
    const { label, readable, writable, bytesPerSecond, uartByteTime_us } = link;
    const close = serialPort ? () => serialPort.close() : undefined;
    const port = new SharedPort({ readable, writable, label, bytesPerSecond, uartByteTime_us, close });
    port.onBroken = (why) =>
      this.log('error', 'PORT_LOST', `${label}: ${why}. Its session is lost: the machine brakes to rest on the path. Plug the board back in and press Add device (or reload the page).`);
    this.list.push({ id: `port-${this.nextId++}`, port, simulated: false, bridged: serialPort === null, serialPort, info: null });
    this.changed = true;
    this.log('info', 'CONNECT', `Connected ${label}${serialPort ? ' (the worker owns its streams)' : ' (through the page)'}.`);
  }

  /** Whether device `id` can be removed on its own (a simulated one goes only with its machine: said in the log). */
  removable(id: string): boolean {
    const device = this.list.find((d) => d.id === id);
    if (device?.simulated) this.log('warning', 'SIM', 'A simulated device goes with its machine: choose another machine from the menu instead.');
    return device !== undefined && !device.simulated;
  }

  /** Removes and closes device `id` (end the author first). */
  async remove(id: string): Promise<void> {
    const device = this.list.find((d) => d.id === id);
    if (!device) return;
    this.list = this.list.filter((d) => d !== device);
    this.changed = true;
    await device.port.close();
  }

  /** Closes every device and stops the simulated machine (end the author first). */
  async closeAll(): Promise<void> {
    for (const d of this.list) await d.port.close();
    this.list = [];
    await this.simulated?.stop();
    this.simulated = null;
    this.changed = true;
  }

  /** Remembers what each device said in its hello (the author's sessions are in link order). */
  learn(maxl: Maxl): void {
    maxl.devices().forEach((report, i) => {
      const d = this.list[i];
      if (!d || !report.firmware) return;
      d.info = { name: report.name, protocol: 0, firmware: report.firmware, clockHz: 0, segmentCapacity: 0, eventCapacity: 0, readers: report.readers };
    });
    this.changed = true;
  }

  /** Something about the devices changed (a device event): report them at the next snapshot. */
  touch(): void {
    this.changed = true;
  }

  /** The devices for the page: when they changed, and otherwise every DEVICE_REPORT_MS (for RTT and sync figures); else null. */
  viewsIfDue(maxl: Maxl | null, now_ms: number): DeviceView[] | null {
    if (!this.changed && now_ms - this.lastReport <= DEVICE_REPORT_MS) return null;
    this.lastReport = now_ms;
    this.changed = false;
    const reports = maxl?.devices() ?? [];
    return this.list.map((d, i) => {
      const r = reports[i];
      const info = d.info;
      return {
        id: d.id,
        label: d.port.label,
        name: r?.firmware ? r.name : (info?.name ?? ''),
        firmware: r?.firmware || info?.firmware || '',
        readers: (r?.readers ?? info?.readers ?? []).map((x) => ({ name: x.name, kind: x.kind })),
        connection: r ? (r.state === 'opening' ? 'connecting' : r.state) : d.port.broken ? 'lost' : 'closed',
        deviceState: r?.deviceState ?? 'unknown',
        rtt_us: r?.rtt_us ?? NaN,
        syncError_us: r?.syncError_us ?? NaN,
        simulated: d.simulated,
      };
    });
  }

  /** A port vanished (unplugged, or the board reset its USB): say what happens next. */
  private portDisappeared(port: SerialPortLike | null, info: { usbVendorId?: number; usbProductId?: number }): void {
    const device = port ? this.list.find((d) => d.serialPort === port) : undefined;
    const label = device?.port.label ?? portLabel(info);
    if (port && !device) return; // not one of the machine's
    this.log(
      'warning',
      'PORT_GONE',
      `${label} disappeared (unplugged, or the board reset its USB). ${device ? 'Its timing stops, so every device brakes to rest on the path; plug it back in and press Add device (or reload the page), then Re-arm.' : 'If it was one of the boards, they brake to rest on the path.'}`,
    );
  }
}
