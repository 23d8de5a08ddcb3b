/**
 * A fake navigator.serial for the WebSerial spec, the page's half, loaded by an
 * init script. The ports it grants are the devices of a simulated machine (real
 * firmware in wasm) running in a worker of their own (fakeSerialWorker.ts), which
 * also keeps which ports are granted. The page's half only asks for ports
 * (requestPort, getPorts, getInfo): as in a real browser, the MAXL worker then
 * finds them through its own navigator.serial, the fake's other half
 * (fakeSerialInWorker.ts, loaded there through the worker test hook), opens them
 * and owns their streams. So the workbench's connect code runs unchanged, and no
 * byte of the boards crosses the page.
 *
 * With `serialInWorkers: false` the fake plays a browser whose workers reach no
 * serial port (navigator.serial and navigator.usb absent there): the page then
 * opens the port itself and bridges its streams to the worker, as the workbench
 * does in such a browser.
 *
 * Ports granted survive a reload (sessionStorage), as a browser's permissions do.
 */
import { rpcClient } from './fakeSerialRpc.ts';
import { streamsOverChannel } from './fakePortStreams.ts';
import type { FakePortInfo } from './fakeSerialWorker.ts';
import type { BoardTraffic } from './fakeBoardLink.ts';

const GRANTED_KEY = 'fakeSerial.granted';

export interface FakeSerialControl {
  /**
   * Ground truth: each simulated motor's step count now, the devices whose ports
   * were opened, requestPort() calls, and for each opened board the chunks that
   * reached it and how many came after their time (fakeBoardLink.ts).
   */
  truth(): Promise<{ steps: Record<string, number>; opened: string[]; requests: number; traffic: Record<string, BoardTraffic> }>;
}

type Call = ReturnType<typeof rpcClient>;

/** A port as the page sees it: its ids; streams only if the page opens it (the bridge). */
class FakePagePort {
  readable: ReadableStream<Uint8Array> | null = null;
  writable: WritableStream<Uint8Array> | null = null;
  constructor(
    readonly info: FakePortInfo,
    private readonly call: Call,
  ) {}

  async open(options: { baudRate: number }): Promise<void> {
    if (!(options.baudRate > 0)) throw new TypeError('baudRate is required');
    if (this.readable) throw new DOMException('The port is already open.', 'InvalidStateError');
    const streams = streamsOverChannel(await this.call<MessagePort>('open', this.info.index));
    this.readable = streams.readable;
    this.writable = streams.writable;
  }

  async close(): Promise<void> {
    this.readable = null;
    this.writable = null;
  }

  getInfo(): { usbVendorId: number; usbProductId: number } {
    return { usbVendorId: this.info.usbVendorId, usbProductId: this.info.usbProductId };
  }
}

/** Starts the fake boards and puts the page's half of the fake on navigator.serial; `maxlWorker` is the channel end the worker test hook carries. */
export async function installFakeSerial(presetId: string, maxlWorker: MessagePort, options: { serialInWorkers: boolean }): Promise<FakeSerialControl> {
  const boards = new Worker(new URL('./fakeSerialWorker.ts', import.meta.url), { type: 'module', name: 'fake-boards' });
  const granted = Number(sessionStorage.getItem(GRANTED_KEY) ?? '0');
  boards.postMessage({ type: 'start', presetId, granted, serialInWorkers: options.serialInWorkers, maxlWorker }, [maxlWorker]);
  const call = rpcClient(boards);
  // One object per port, as a browser keeps them: getPorts() returns the same ones requestPort() did.
  const ports = new Map<number, FakePagePort>();
  const portOf = (info: FakePortInfo) => ports.get(info.index) ?? ports.set(info.index, new FakePagePort(info, call)).get(info.index)!;
  const serial = {
    async requestPort(): Promise<FakePagePort> {
      const answer = await call<{ port: FakePortInfo; granted: number }>('requestPort');
      sessionStorage.setItem(GRANTED_KEY, String(answer.granted));
      return portOf(answer.port);
    },
    async getPorts(): Promise<FakePagePort[]> {
      return (await call<FakePortInfo[]>('getPorts')).map(portOf);
    },
  };
  Object.defineProperty(navigator, 'serial', { value: serial, configurable: true });
  return { truth: () => call('truth') };
}
