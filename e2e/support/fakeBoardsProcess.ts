/**
 * The fake boards behind the fake navigator.serial, in a Node process of their
 * own, outside the browser (as real boards are computers of their own, off the
 * author's threads): the workbench's own simulated machine (real firmware in
 * wasm), one port per device, behind a WebSocket server on localhost. Started
 * and stopped by the spec (fakeBoards.ts), which reads the server's address from
 * this process's first line of output.
 *
 * It also plays the browser's permission store: which ports are granted (the
 * page passes the count it kept in sessionStorage, so grants survive a reload).
 *
 * Each page load is a session: a fresh simulated machine, as a fresh browser
 * worker was before, named by an id the page chose. Sockets (all carry
 * `?session=ID&preset=…&granted=N&serialInWorkers=0|1`; the first to come makes
 * the session):
 *  - `/control?role=page`: the page's fake (fakeSerial.ts) calls requestPort,
 *    getPorts, open (the bridge of a browser whose workers reach no port) and
 *    the spec's ground truth. When it closes (the page reloads or goes), the
 *    session's machine stops.
 *  - `/control?role=worker`: the MAXL worker's fake (fakeSerialInWorker.ts) calls
 *    serialInWorkers, getPorts and open.
 *  - `/port?…&token=T`: a port's streams, opened with the token that `open`
 *    returned, once (fakeBoardLink.ts; a device's link is not handed out twice).
 *
 * The boards run on paced virtual time: like firmware, which loops without
 * waiting on anyone's timers, every device loop and link delay happens at its
 * own time. Each wake of their scheduler first reads the chunks that came
 * meanwhile (fakeBoardLink.ts), so the bytes the author wrote reach a board at
 * the time it wrote them even when this process was held back.
 */
import { randomUUID } from 'node:crypto';
import type { IncomingMessage } from 'node:http';
import { WebSocketServer, type WebSocket } from 'ws';
import { PacedScheduler } from '../../core/index.ts';
import type { Link } from '../../core/net/link.ts';
import { createSimulatedMachine, type SimulatedMachine } from '../../core/sim/machine.ts';
import { nodeWasmLoader } from '../../core/sim/device/nodeWasmLoader.ts';
import { PRESETS } from '../../core/sim/presets/index.ts';
import { RpcError, rpcServer, type FakePortInfo, type TextChannel } from './fakeSerialRpc.ts';
import { connectBoard, wakeAfterIo, type BoardTraffic } from './fakeBoardLink.ts';

/** What getInfo() says for each device, in grant order: two identical Unos and a Mega. */
const USB_IDS = [
  { usbVendorId: 0x2341, usbProductId: 0x0043 },
  { usbVendorId: 0x2341, usbProductId: 0x0043 },
  { usbVendorId: 0x2341, usbProductId: 0x0042 },
];

interface Board {
  name: string;
  link: Link;
  /** Set once opened: the bytes that reached it from its opener. */
  traffic: BoardTraffic | null;
}

interface Session {
  scheduler: PacedScheduler;
  /** Resolves once the machine runs. */
  machine: Promise<{ sim: SimulatedMachine; boards: Board[] }>;
  granted: number;
  requests: number;
  opened: string[];
  /** Whether the MAXL worker's navigator has serial ports (false: a browser that needs the bridge). */
  serialInWorkers: boolean;
  /** open()'s one-time tokens → board index. */
  tokens: Map<string, number>;
  sockets: Set<WebSocket>;
}

/** µs between device loop() calls while busy: the workbench's own simulated machines' (app/worker/simulatedMachines.ts, which reads its firmware over fetch and cannot load in Node). */
const LOOP_PERIOD_US = 100;

const loader = nodeWasmLoader();
const sessions = new Map<string, Session>();

function info(index: number): FakePortInfo {
  return { index, ...USB_IDS[index % USB_IDS.length] };
}

/** The session a socket names, made by the first socket to come; a bad query is said so. */
function sessionOf(query: URLSearchParams): Session {
  const id = query.get('session');
  if (!id) throw new Error('no session= in the fake boards URL');
  const existing = sessions.get(id);
  if (existing) return existing;
  const presetId = query.get('preset') ?? '';
  const make = PRESETS[presetId];
  if (!make) throw new Error(`there is no simulated machine "${presetId}" (presets: ${Object.keys(PRESETS).join(', ')})`);
  const granted = Number(query.get('granted') ?? '0');
  if (!Number.isInteger(granted) || granted < 0) throw new Error(`granted= must be a whole number ≥ 0, not "${query.get('granted')}"`);
  const scheduler = new PacedScheduler({ wake: wakeAfterIo() });
  const machine = createSimulatedMachine(make(), scheduler, {
    loader,
    seed: 1,
    loopPeriod_us: LOOP_PERIOD_US,
    onError: (err) => console.error('fake boards:', err),
  }).then((sim) => ({ sim, boards: Object.entries(sim.links).map(([name, link]): Board => ({ name, link, traffic: null })) }));
  const session: Session = { scheduler, machine, granted, requests: 0, opened: [], serialInWorkers: query.get('serialInWorkers') !== '0', tokens: new Map(), sockets: new Set() };
  sessions.set(id, session);
  return session;
}

/** Stops a session's machine and closes its sockets (its page went). */
function endSession(id: string, session: Session): void {
  sessions.delete(id);
  session.scheduler.stop();
  for (const s of session.sockets) s.close(1001, 'the page went');
  void session.machine.then(({ sim }) => sim.stop()).catch(() => undefined);
}

/** A granted port's one-time token for its streams' socket. */
async function open(session: Session, index: number): Promise<string> {
  const { boards } = await session.machine;
  const board = boards[index];
  if (!board || index >= session.granted) throw new RpcError('NotFoundError', `port ${index} is not granted`);
  if (board.traffic || [...session.tokens.values()].includes(index)) throw new RpcError('InvalidStateError', 'The port is already open.');
  const token = randomUUID();
  session.tokens.set(token, index);
  return token;
}

async function answer(session: Session, role: string, call: string, args: unknown): Promise<unknown> {
  const { sim, boards } = await session.machine;
  const grantedPorts = () => boards.slice(0, session.granted).map((_, i) => info(i));
  switch (`${role} ${call}`) {
    case 'page requestPort':
      session.requests++;
      if (session.granted >= boards.length) throw new RpcError('NotFoundError', 'No port selected by the user.');
      session.granted++;
      return { port: info(session.granted - 1), granted: session.granted };
    case 'page getPorts':
    case 'worker getPorts':
      return grantedPorts();
    case 'page open':
    case 'worker open':
      return open(session, args as number);
    case 'worker serialInWorkers':
      return session.serialInWorkers;
    case 'page truth': {
      sim.sync();
      const traffic = Object.fromEntries(boards.filter((b) => b.traffic).map((b) => [b.name, { ...b.traffic! }]));
      // The boards' own delays: wakes of their scheduler over 5 ms late or long (PacingStall).
      const stalls = session.scheduler.stalls;
      const pacing = { stalls: stalls.length, worstLate_ms: Math.max(0, ...stalls.map((s) => s.late_ms)), worstRun_ms: Math.max(0, ...stalls.map((s) => s.run_ms)) };
      return { steps: sim.plant.motorSteps(), opened: session.opened, requests: session.requests, traffic, pacing };
    }
  }
  throw new RpcError('NotSupportedError', `the fake boards have no ${role} call ${call}`);
}

function textChannelOf(socket: WebSocket): TextChannel {
  return {
    send: (text) => socket.send(text),
    onText: (listener) =>
      socket.on('message', (data: Buffer, isBinary: boolean) => {
        if (!isBinary) listener(data.toString());
      }),
  };
}

/** Connects a port's streams socket to its board. */
async function connectPort(session: Session, socket: WebSocket, token: string): Promise<void> {
  const index = session.tokens.get(token);
  if (index === undefined) return socket.close(1008, 'no such open() token (a port opens once)');
  session.tokens.delete(token);
  const { boards } = await session.machine;
  const board = boards[index];
  board.traffic = connectBoard(board.link, socket, session.scheduler);
  session.opened.push(board.name);
}

function accept(socket: WebSocket, request: IncomingMessage): void {
  const url = new URL(request.url ?? '/', 'ws://localhost');
  const id = url.searchParams.get('session') ?? '';
  let session: Session;
  try {
    session = sessionOf(url.searchParams);
  } catch (err) {
    return socket.close(1008, (err as Error).message.slice(0, 120));
  }
  session.sockets.add(socket);
  socket.on('close', () => session.sockets.delete(socket));
  if (url.pathname === '/port') {
    void connectPort(session, socket, url.searchParams.get('token') ?? '');
    return;
  }
  const role = url.searchParams.get('role');
  if (url.pathname !== '/control' || (role !== 'page' && role !== 'worker')) return socket.close(1008, `no such fake boards socket ${url.pathname}?role=${role}`);
  rpcServer(textChannelOf(socket), (call, args) => answer(session, role, call, args));
  if (role === 'page') socket.on('close', () => endSession(id, session));
}

// Compile every preset's firmware before listening, so that a session's machine starts at
// once: its paced clock starts when the session does, and a board still compiling would
// answer its first messages late by the compile's time.
await Promise.all(Object.values(PRESETS).flatMap((make) => make().devices.map((d) => loader(d.example))));

const server = new WebSocketServer({ host: '127.0.0.1', port: 0 });
server.on('connection', accept);
server.on('listening', () => {
  const address = server.address();
  if (!address || typeof address === 'string') throw new Error(`the fake boards listen on a pipe, not a port: ${String(address)}`);
  // The spec's fakeBoards.ts waits for this line.
  console.log(`fake boards listening on ws://127.0.0.1:${address.port}`);
});
// Go with the spec: its end of stdin closes when it stops us or dies.
process.stdin.resume();
process.stdin.on('end', () => process.exit(0));
