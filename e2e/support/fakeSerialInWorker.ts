/**
 * The fake navigator.serial's half in the MAXL worker, loaded there through the
 * worker test hook (docs/test-hooks.md). A worker's navigator.serial has
 * getPorts() but no requestPort(); its ports are the ones granted on the page,
 * which the fake boards' worker keeps. open() has that worker connect the
 * device's board to a MessageChannel whose other end comes here, and the port's
 * streams run over it (fakePortStreams.ts): no byte crosses the page.
 * Or, if the spec plays a browser without serial ports in workers, it takes
 * navigator.serial and navigator.usb away here.
 */
/// <reference lib="webworker" />
import { rpcClient } from './fakeSerialRpc.ts';
import { streamsOverChannel } from './fakePortStreams.ts';
import type { FakePortInfo } from './fakeSerialWorker.ts';

type Call = ReturnType<typeof rpcClient>;

class FakeWorkerPort extends EventTarget {
  readable: ReadableStream<Uint8Array> | null = null;
  writable: WritableStream<Uint8Array> | null = null;
  constructor(
    private readonly info: FakePortInfo,
    private readonly call: Call,
  ) {
    super();
  }

  async open(options: { baudRate: number }): Promise<void> {
    if (!(options.baudRate > 0)) throw new TypeError('baudRate is required');
    if (this.readable) throw new DOMException('The port is already open.', 'InvalidStateError');
    const streams = streamsOverChannel(await this.call<MessagePort>('open', this.info.index));
    this.readable = streams.readable;
    this.writable = streams.writable;
  }

  /** Lets go of the streams (the fake boards cannot hand out a device's link twice: a closed fake port stays closed). */
  async close(): Promise<void> {
    this.readable = null;
    this.writable = null;
  }

  getInfo(): { usbVendorId: number; usbProductId: number } {
    return { usbVendorId: this.info.usbVendorId, usbProductId: this.info.usbProductId };
  }
}

export async function installInWorker(port: MessagePort | null): Promise<void> {
  if (!port) throw new Error('the fake serial needs the channel to the fake boards (the hook carries none)');
  const call = rpcClient(port);
  if (!(await call<boolean>('serialInWorkers'))) {
    // A browser whose workers reach no port: the workbench must bridge through the page.
    Object.defineProperty(navigator, 'serial', { value: undefined, configurable: true });
    Object.defineProperty(navigator, 'usb', { value: undefined, configurable: true });
    return;
  }
  const ports = new Map<number, FakeWorkerPort>();
  const portOf = (info: FakePortInfo) => ports.get(info.index) ?? ports.set(info.index, new FakeWorkerPort(info, call)).get(info.index)!;
  const serial = Object.assign(new EventTarget(), {
    async getPorts(): Promise<FakeWorkerPort[]> {
      return (await call<FakePortInfo[]>('getPorts')).map(portOf);
    },
  });
  Object.defineProperty(navigator, 'serial', { value: serial, configurable: true });
}
