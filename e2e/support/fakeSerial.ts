/**
 * A fake navigator.serial for the WebSerial spec, the page's half, loaded by an
 * init script. The ports it grants are the devices of a simulated machine (real
 * firmware in wasm) running outside the browser, in a Node process of their own
 * (fakeBoardsProcess.ts), which also keeps which ports are granted. The page's
 * half only asks for ports (requestPort, getPorts, getInfo): as in a real
 * browser, the MAXL worker then finds them through its own navigator.serial, the
 * fake's other half (fakeSerialInWorker.ts, loaded there through the worker test
 * hook), opens them and owns their streams. So the workbench's connect code runs
 * unchanged, and no byte of the boards crosses the page.
 *
 * Each page load is a session of the boards' process: a fresh machine, which
 * stops when the page goes. The page tells the worker's half where to find it
 * over the hook's channel.
 *
 * With `serialInWorkers: false` the fake plays a browser whose workers reach no
 * serial port (navigator.serial and navigator.usb absent there): the page then
 * opens the port itself and bridges its streams to the worker, as the workbench
 * does in such a browser.
 *
 * Ports granted survive a reload (sessionStorage), as a browser's permissions do.
 */
import { connectSocket, rpcClient, sessionUrl, textChannelOf, type FakeBoardsAddress, type FakePortInfo } from './fakeSerialRpc.ts';
import { streamsOverSocket } from './fakePortStreams.ts';
import type { BoardTraffic } from './fakeBoardLink.ts';

const GRANTED_KEY = 'fakeSerial.granted';

export interface FakeSerialControl {
  /**
   * Ground truth: each simulated motor's step count now, the devices whose ports
   * were opened, requestPort() calls, and for each opened board the chunks that
   * reached it and how many came after their time (fakeBoardLink.ts); and the
   * boards' own pacing: how many wakes of their scheduler came over 5 ms late or
   * ran over 5 ms, and the worst of each (core/time/pacedScheduler.ts).
   */
  truth(): Promise<{ steps: Record<string, number>; opened: string[]; requests: number; traffic: Record<string, BoardTraffic>; pacing: BoardsPacing }>;
}

/** The fake boards' scheduler's stalls (PacingStall): the process held back (late) or busy (run). */
export interface BoardsPacing {
  stalls: number;
  worstLate_ms: number;
  worstRun_ms: number;
}

type Call = ReturnType<typeof rpcClient>;

/** A port as the page sees it: its ids; streams only if the page opens it (the bridge). */
class FakePagePort {
  readable: ReadableStream<Uint8Array> | null = null;
  writable: WritableStream<Uint8Array> | null = null;
  private closeSocket: (() => void) | null = null;
  constructor(
    readonly info: FakePortInfo,
    private readonly call: Call,
    private readonly session: string,
  ) {}

  async open(options: { baudRate: number }): Promise<void> {
    if (!(options.baudRate > 0)) throw new TypeError('baudRate is required');
    if (this.readable) throw new DOMException('The port is already open.', 'InvalidStateError');
    const token = await this.call<string>('open', this.info.index);
    const streams = await streamsOverSocket(sessionUrl(this.session, '/port', { token }));
    this.readable = streams.readable;
    this.writable = streams.writable;
    this.closeSocket = streams.close;
  }

  async close(): Promise<void> {
    this.closeSocket?.();
    this.readable = null;
    this.writable = null;
  }

  getInfo(): { usbVendorId: number; usbProductId: number } {
    return { usbVendorId: this.info.usbVendorId, usbProductId: this.info.usbProductId };
  }
}

/**
 * Starts a session of the fake boards at `boardsUrl` (fakeBoards.ts started them)
 * and puts the page's half of the fake on navigator.serial; `maxlWorker` is the
 * channel end the worker test hook carries to the worker's half.
 */
export async function installFakeSerial(boardsUrl: string, presetId: string, maxlWorker: MessagePort, options: { serialInWorkers: boolean }): Promise<FakeSerialControl> {
  const granted = sessionStorage.getItem(GRANTED_KEY) ?? '0';
  const session = sessionUrl(boardsUrl, '/', { session: crypto.randomUUID(), preset: presetId, granted, serialInWorkers: options.serialInWorkers ? '1' : '0' });
  maxlWorker.postMessage({ session } satisfies FakeBoardsAddress);
  maxlWorker.close();
  const call = rpcClient(textChannelOf(await connectSocket(sessionUrl(session, '/control', { role: 'page' }))));
  // One object per port, as a browser keeps them: getPorts() returns the same ones requestPort() did.
  const ports = new Map<number, FakePagePort>();
  const portOf = (info: FakePortInfo) => ports.get(info.index) ?? ports.set(info.index, new FakePagePort(info, call, session)).get(info.index)!;
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
