/**
 * The fake boards behind the fake navigator.serial, in a worker of their own (as
 * real boards are computers of their own, off the author's threads): the
 * workbench's own simulated machine, one port per device. It also plays the
 * browser's permission store: which ports are granted (the page passes the count
 * it kept in sessionStorage, so grants survive a reload).
 *
 * Two ends call it (fakeSerialRpc.ts):
 *  - the page's fake (fakeSerial.ts): requestPort, getPorts, and the spec's
 *    ground truth (motor steps, ports opened); and open, for the bridge of a
 *    browser whose workers reach no port;
 *  - the MAXL worker's fake (fakeSerialInWorker.ts), over a MessageChannel:
 *    whether this browser's workers have serial ports at all, getPorts and open.
 *    Opening a port hands the opener one end of a MessageChannel to its board
 *    (fakePortStreams.ts, fakeBoardLink.ts): from the MAXL worker's open, no
 *    byte crosses the page.
 *
 * The boards run on paced virtual time: like firmware, which loops without
 * waiting on a browser's timers, every device loop and link delay happens at its
 * own time; only the author, in the MAXL worker, runs on the wall clock. Each
 * wake of their scheduler first reads the chunks that came meanwhile, so that the
 * bytes the author wrote reach a board at the time it wrote them even when this
 * worker was held back (fakeBoardLink.ts).
 */
/// <reference lib="webworker" />
import { PacedScheduler } from '../../core/index.ts';
import type { Link } from '../../core/net/link.ts';
import type { SimulatedMachine } from '../../core/sim/machine.ts';
import { startSimulatedMachine } from '../../app/worker/simulatedMachines.ts';
import { RpcError, rpcServer } from './fakeSerialRpc.ts';
import { connectBoard, wakeAfterMail, type BoardTraffic } from './fakeBoardLink.ts';

const scope = self as unknown as DedicatedWorkerGlobalScope;

/** What getInfo() says for each device, in grant order: two identical Unos and a Mega. */
const USB_IDS = [
  { usbVendorId: 0x2341, usbProductId: 0x0043 },
  { usbVendorId: 0x2341, usbProductId: 0x0043 },
  { usbVendorId: 0x2341, usbProductId: 0x0042 },
];

export interface FakePortInfo {
  index: number;
  usbVendorId: number;
  usbProductId: number;
}

interface Board {
  name: string;
  link: Link;
  /** Set once opened: the bytes that reached it from its opener. */
  traffic: BoardTraffic | null;
}

const scheduler = new PacedScheduler({ wake: wakeAfterMail() });
let sim: SimulatedMachine;
let boards: Board[] = [];
let granted = 0;
let requests = 0;
const opened: string[] = [];
/** Whether the MAXL worker's navigator has serial ports (false: a browser that needs the bridge). */
let serialInWorkers = true;
let started!: () => void;
const ready = new Promise<void>((resolve) => (started = resolve));

function info(index: number): FakePortInfo {
  return { index, ...USB_IDS[index % USB_IDS.length] };
}

function grantedPorts(): FakePortInfo[] {
  return boards.slice(0, granted).map((_, i) => info(i));
}

/** Connects a granted port's board to whoever opens it, over a channel (once: a device's link cannot be handed out twice). */
function open(index: number): { value: unknown; transfer: Transferable[] } {
  const board = boards[index];
  if (!board || index >= granted) throw new RpcError('NotFoundError', `port ${index} is not granted`);
  if (board.traffic) throw new RpcError('InvalidStateError', 'The port is already open.');
  const channel = new MessageChannel();
  board.traffic = connectBoard(board.link, channel.port1, scheduler);
  opened.push(board.name);
  return { value: channel.port2, transfer: [channel.port2] };
}

/** For each opened board, the bytes that reached it and how many came after their time. */
function traffic(): Record<string, BoardTraffic> {
  return Object.fromEntries(boards.filter((b) => b.traffic).map((b) => [b.name, { ...b.traffic! }]));
}

/** The page's calls. */
async function fromPage(call: string, args: unknown): Promise<{ value: unknown; transfer?: Transferable[] }> {
  await ready;
  switch (call) {
    case 'requestPort':
      requests++;
      if (granted >= boards.length) throw new RpcError('NotFoundError', 'No port selected by the user.');
      granted++;
      return { value: { port: info(granted - 1), granted } };
    case 'getPorts':
      return { value: grantedPorts() };
    case 'open':
      return open(args as number);
    case 'truth':
      sim.sync();
      return { value: { steps: sim.plant.motorSteps(), opened, requests, traffic: traffic() } };
  }
  throw new RpcError('NotSupportedError', `the fake boards have no page call ${call}`);
}

/** The MAXL worker's calls. */
async function fromMaxlWorker(call: string, args: unknown): Promise<{ value: unknown; transfer?: Transferable[] }> {
  await ready;
  switch (call) {
    case 'serialInWorkers':
      return { value: serialInWorkers };
    case 'getPorts':
      return { value: grantedPorts() };
    case 'open':
      return open(args as number);
  }
  throw new RpcError('NotSupportedError', `the fake boards have no worker call ${call}`);
}

scope.addEventListener('message', async (m: MessageEvent) => {
  const msg = m.data as { type?: string; presetId: string; granted: number; serialInWorkers: boolean; maxlWorker: MessagePort };
  if (msg.type !== 'start') return;
  granted = msg.granted;
  serialInWorkers = msg.serialInWorkers;
  rpcServer(msg.maxlWorker, fromMaxlWorker);
  sim = await startSimulatedMachine(msg.presetId, scheduler, (err) => console.error('fake boards:', err));
  boards = Object.entries(sim.links).map(([name, link]) => ({ name, link, traffic: null }));
  started();
});
rpcServer(scope as unknown as Parameters<typeof rpcServer>[0], fromPage);
