/**
 * The fake navigator.serial's half in the MAXL worker, loaded there through the
 * worker test hook (docs/test-hooks.md). A worker's navigator.serial has
 * getPorts() but no requestPort(); its ports are the ones granted on the page,
 * which the fake boards' Node process keeps (fakeBoardsProcess.ts). The page
 * sends, over the hook's channel, the address of its session there; open() asks
 * the boards for a token and opens the port's streams over a WebSocket of their
 * own (fakePortStreams.ts): no byte crosses the page.
 * Or, if the spec plays a browser without serial ports in workers, it takes
 * navigator.serial and navigator.usb away here.
 */
/// <reference lib="webworker" />
import { connectSocket, rpcClient, sessionUrl, textChannelOf, type FakeBoardsAddress, type FakePortInfo } from './fakeSerialRpc.ts';
import { streamsOverSocket } from './fakePortStreams.ts';

type Call = ReturnType<typeof rpcClient>;

class FakeWorkerPort extends EventTarget {
  readable: ReadableStream<Uint8Array> | null = null;
  writable: WritableStream<Uint8Array> | null = null;
  private closeSocket: (() => void) | null = null;
  constructor(
    private readonly info: FakePortInfo,
    private readonly call: Call,
    private readonly session: string,
  ) {
    super();
  }

  async open(options: { baudRate: number }): Promise<void> {
    if (!(options.baudRate > 0)) throw new TypeError('baudRate is required');
    if (this.readable) throw new DOMException('The port is already open.', 'InvalidStateError');
    const token = await this.call<string>('open', this.info.index);
    const streams = await streamsOverSocket(sessionUrl(this.session, '/port', { token }));
    this.readable = streams.readable;
    this.writable = streams.writable;
    this.closeSocket = streams.close;
  }

  /** Lets go of the streams (the fake boards cannot hand out a device's link twice: a closed fake port stays closed). */
  async close(): Promise<void> {
    this.closeSocket?.();
    this.readable = null;
    this.writable = null;
  }

  getInfo(): { usbVendorId: number; usbProductId: number } {
    return { usbVendorId: this.info.usbVendorId, usbProductId: this.info.usbProductId };
  }
}

/** The page's first message on the hook's channel: where the session's boards are. */
function boardsAddress(port: MessagePort): Promise<FakeBoardsAddress> {
  return new Promise((resolve) => {
    port.onmessage = (m: MessageEvent<FakeBoardsAddress>) => {
      port.close();
      resolve(m.data);
    };
  });
}

export async function installInWorker(port: MessagePort | null): Promise<void> {
  if (!port) throw new Error('the fake serial needs the channel from the page (the hook carries none)');
  const { session } = await boardsAddress(port);
  const call = rpcClient(textChannelOf(await connectSocket(sessionUrl(session, '/control', { role: 'worker' }))));
  if (!(await call<boolean>('serialInWorkers'))) {
    // A browser whose workers reach no port: the workbench must bridge through the page.
    Object.defineProperty(navigator, 'serial', { value: undefined, configurable: true });
    Object.defineProperty(navigator, 'usb', { value: undefined, configurable: true });
    return;
  }
  const ports = new Map<number, FakeWorkerPort>();
  const portOf = (info: FakePortInfo) => ports.get(info.index) ?? ports.set(info.index, new FakeWorkerPort(info, call, session)).get(info.index)!;
  const serial = Object.assign(new EventTarget(), {
    async getPorts(): Promise<FakeWorkerPort[]> {
      return (await call<FakePortInfo[]>('getPorts')).map(portOf);
    },
  });
  Object.defineProperty(navigator, 'serial', { value: serial, configurable: true });
}
