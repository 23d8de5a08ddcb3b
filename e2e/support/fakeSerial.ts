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
 * Ports granted survive a reload (sessionStorage), as a browser's permissions do.
 */
import { rpcClient } from './fakeSerialRpc.ts';
import type { FakePortInfo } from './fakeSerialWorker.ts';

const GRANTED_KEY = 'fakeSerial.granted';

export interface FakeSerialControl {
  /** Ground truth: each simulated motor's step count now, the devices whose ports were opened, requestPort() calls. */
  truth(): Promise<{ steps: Record<string, number>; opened: string[]; requests: number }>;
}

/** A port as the page sees it: no streams (the worker opens it), only its ids. */
class FakePagePort {
  readonly readable = null;
  readonly writable = null;
  constructor(readonly info: FakePortInfo) {}

  async open(): Promise<void> {
    throw new DOMException('The fake ports open in the MAXL worker, not on the page.', 'NotSupportedError');
  }

  async close(): Promise<void> {}

  getInfo(): { usbVendorId: number; usbProductId: number } {
    return { usbVendorId: this.info.usbVendorId, usbProductId: this.info.usbProductId };
  }
}

/** Starts the fake boards and puts the page's half of the fake on navigator.serial; `maxlWorker` is the channel end the worker test hook carries. */
export async function installFakeSerial(presetId: string, maxlWorker: MessagePort): Promise<FakeSerialControl> {
  const boards = new Worker(new URL('./fakeSerialWorker.ts', import.meta.url), { type: 'module', name: 'fake-boards' });
  const granted = Number(sessionStorage.getItem(GRANTED_KEY) ?? '0');
  boards.postMessage({ type: 'start', presetId, granted, maxlWorker }, [maxlWorker]);
  const call = rpcClient(boards);
  // One object per port, as a browser keeps them: getPorts() returns the same ones requestPort() did.
  const ports = new Map<number, FakePagePort>();
  const portOf = (info: FakePortInfo) => ports.get(info.index) ?? ports.set(info.index, new FakePagePort(info)).get(info.index)!;
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
