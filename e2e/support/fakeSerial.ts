/**
 * A fake navigator.serial for the WebSerial spec, loaded into the page by an init
 * script. Each port it grants is one device of a simulated machine (real firmware
 * in wasm, in real time, in a worker of its own: fakeSerialWorker.ts), and its
 * readable/writable are that device's link: so the workbench's own connect code
 * (requestPort, open, getInfo, getPorts, transferring the streams to the MAXL
 * worker) runs unchanged.
 *
 * Ports granted survive a reload (sessionStorage), as a browser's permissions do.
 */
const GRANTED_KEY = 'fakeSerial.granted';

interface WorkerPort {
  name: string;
  readable: ReadableStream<Uint8Array>;
  writable: WritableStream<Uint8Array>;
}

export interface FakeSerialControl {
  /** Device names in the order requestPort() hands them out. */
  devices: string[];
  /** requestPort() calls so far. */
  requests: number;
  /** Ports opened so far. */
  opened: string[];
  /** Ground truth: each simulated motor's step count now. */
  motorSteps(): Promise<Record<string, number>>;
}

class FakePort {
  readable: ReadableStream<Uint8Array> | null = null;
  writable: WritableStream<Uint8Array> | null = null;
  constructor(
    private readonly link: WorkerPort,
    private readonly index: number,
    private readonly control: FakeSerialControl,
  ) {}

  async open(options: { baudRate: number }): Promise<void> {
    if (!(options.baudRate > 0)) throw new TypeError('baudRate is required');
    if (this.readable) throw new DOMException('The port is already open.', 'InvalidStateError');
    this.readable = this.link.readable;
    this.writable = this.link.writable;
    this.control.opened.push(this.link.name);
  }

  async close(): Promise<void> {
    this.readable = null;
    this.writable = null;
  }

  getInfo(): { usbVendorId: number; usbProductId: number } {
    return { usbVendorId: 0x2341, usbProductId: 0x0043 + this.index };
  }
}

export async function installFakeSerial(presetId: string): Promise<FakeSerialControl> {
  const worker = new Worker(new URL('./fakeSerialWorker.ts', import.meta.url), { type: 'module', name: 'fake-boards' });
  const truths = new Map<number, (steps: Record<string, number>) => void>();
  let nextTruth = 1;
  const links = await new Promise<WorkerPort[]>((resolve) => {
    worker.onmessage = (m: MessageEvent) => {
      if (m.data.type === 'ready') resolve(m.data.ports as WorkerPort[]);
      else if (m.data.type === 'truth') truths.get(m.data.id)?.(m.data.steps);
    };
    worker.postMessage({ type: 'start', presetId });
  });
  const control: FakeSerialControl = {
    devices: links.map((l) => l.name),
    requests: 0,
    opened: [],
    motorSteps: () =>
      new Promise((resolve) => {
        const id = nextTruth++;
        truths.set(id, resolve);
        worker.postMessage({ type: 'truth', id });
      }),
  };
  const ports = links.map((link, i) => new FakePort(link, i, control));
  const granted = (): number => Number(sessionStorage.getItem(GRANTED_KEY) ?? '0');
  const serial = {
    async requestPort(): Promise<FakePort> {
      control.requests++;
      const n = granted();
      if (n >= ports.length) throw new DOMException('No port selected by the user.', 'NotFoundError');
      sessionStorage.setItem(GRANTED_KEY, String(n + 1));
      return ports[n];
    },
    async getPorts(): Promise<FakePort[]> {
      return ports.slice(0, granted());
    },
  };
  Object.defineProperty(navigator, 'serial', { value: serial, configurable: true });
  return control;
}
