/**
 * The Node serialport link, on real pseudo-terminals (socat makes a connected
 * pair, as a USB-serial board and its tty would be). The last test puts a
 * simulated board (real firmware in wasm, in real time) behind the far end and
 * runs the runtime's begin() through the serialport link, unchanged.
 */
import { spawn, type ChildProcess } from 'node:child_process';
import { afterEach, describe, expect, it } from 'vitest';
import { openSerialportLink } from './serialportLink.ts';
import { createMAXL } from '../maxl.ts';
import { RealScheduler } from '../time/realScheduler.ts';
import { createSimulatedMachine } from '../sim/machine.ts';
import { nodeWasmLoader } from '../sim/device/nodeWasmLoader.ts';
import { accelRig } from '../sim/presets/index.ts';
import type { Link } from './link.ts';

const children: ChildProcess[] = [];
const closers: Array<() => Promise<void>> = [];
afterEach(async () => {
  for (const c of closers.splice(0)) await c();
  for (const c of children.splice(0)) c.kill();
});

/** Two connected pseudo-terminals from socat: bytes written to one are read from the other. */
function ptyPair(): Promise<[string, string]> {
  const socat = spawn('socat', ['-d', '-d', 'pty,raw,echo=0', 'pty,raw,echo=0']);
  children.push(socat);
  return new Promise((resolve, reject) => {
    const paths: string[] = [];
    let text = '';
    socat.on('error', (e) => reject(new Error(`socat is needed for this test (bash scripts/install-system-deps.sh): ${e.message}`)));
    socat.stderr.on('data', (d: Buffer) => {
      text += d.toString();
      for (const m of text.matchAll(/PTY is (\S+)/g)) if (!paths.includes(m[1])) paths.push(m[1]);
      if (paths.length === 2 && /starting data transfer loop/.test(text)) resolve([paths[0], paths[1]]);
    });
    socat.on('exit', (code) => reject(new Error(`socat exited (${code}): ${text}`)));
  });
}

async function open(path: string): Promise<Link> {
  const link = await openSerialportLink(path);
  closers.push(() => link.close?.() ?? Promise.resolve());
  return link;
}

/** Reads from `reader` until `n` bytes have come. */
async function readBytes(reader: ReadableStreamDefaultReader<Uint8Array>, n: number): Promise<number[]> {
  const got: number[] = [];
  while (got.length < n) {
    const { value, done } = await reader.read();
    if (done) break;
    got.push(...value);
  }
  return got;
}

/** Copies every chunk from `from` into `to` until either ends. */
async function pump(from: ReadableStream<Uint8Array>, to: WritableStream<Uint8Array>): Promise<void> {
  const w = to.getWriter();
  try {
    for await (const chunk of from as unknown as AsyncIterable<Uint8Array>) await w.write(chunk);
  } catch {
    // one end closed
  }
}

describe('serialport link', () => {
  it('carries bytes both ways, in order, as Uint8Array chunks', async () => {
    const [a, b] = await ptyPair();
    const left = await open(a);
    const right = await open(b);
    const payload = Uint8Array.from({ length: 3000 }, (_, i) => (i * 7 + 3) & 0xff);
    const w = left.writable.getWriter();
    const r = right.readable.getReader();
    const reading = readBytes(r, payload.length);
    await w.write(payload.subarray(0, 1000));
    await w.write(payload.subarray(1000));
    expect(await reading).toEqual([...payload]);

    const back = right.writable.getWriter();
    const rl = left.readable.getReader();
    await back.write(Uint8Array.of(0, 1, 2, 255));
    const first = await rl.read();
    expect(first.value).toBeInstanceOf(Uint8Array);
    expect([...(first.value as Uint8Array), ...(await readBytes(rl, 4 - (first.value?.length ?? 0)))]).toEqual([0, 1, 2, 255]);
    r.releaseLock();
    rl.releaseLock();
    w.releaseLock();
    back.releaseLock();
  });

  it('ends the readable when the port is closed', async () => {
    const [a] = await ptyPair();
    const link = await openSerialportLink(a);
    const reader = link.readable.getReader();
    await link.close?.();
    expect((await reader.read()).done).toBe(true);
  });

  it('declares its bytes/s and, unless told the board is native USB, a UART byte time (10 bits at the baud)', async () => {
    const [a, b] = await ptyPair();
    const uno = await open(a);
    expect(uno.bytesPerSecond).toBe(25_000);
    expect(uno.uartByteTime_us).toBe(40);
    const native = await openSerialportLink(b, { baudRate: 115_200, uart: false });
    closers.push(() => native.close?.() ?? Promise.resolve());
    expect(native.uartByteTime_us).toBeUndefined();
  });

  it('names the port it could not open', async () => {
    await expect(openSerialportLink('/dev/no-such-maxl-board')).rejects.toMatchObject({
      code: 'DEVICE_UNAVAILABLE',
      field: 'path',
      message: expect.stringMatching(/^path: cannot open serial port \/dev\/no-such-maxl-board: /),
    });
  });

  it('runs a device session: begin() over a pty to a simulated board', async () => {
    const [a, b] = await ptyPair();
    const scheduler = new RealScheduler();
    const preset = accelRig();
    const sim = await createSimulatedMachine(preset, scheduler, { seed: 3, loader: nodeWasmLoader(), loopPeriod_us: 200 });
    closers.push(() => sim.stop());
    // Each simulated board behind its own pty pair; the author opens the far ends.
    const links: Link[] = [];
    for (const [name, simLink] of Object.entries(sim.links)) {
      const [near, far] = name === Object.keys(sim.links)[0] ? [b, a] : await ptyPair();
      const board = await open(near);
      void pump(board.readable, simLink.writable);
      void pump(simLink.readable, board.writable);
      links.push(await open(far));
    }
    const maxl = createMAXL(sim.config, { links, scheduler });
    closers.unshift(async () => maxl.close());
    const devices = await maxl.begin();
    expect(devices.map((d) => d.name).sort()).toEqual(Object.keys(sim.links).sort());
    for (const d of devices) expect(d.readers.length).toBeGreaterThan(0);
    expect(links.map((l) => l.label).sort()).toEqual(expect.arrayContaining([a]));
  }, 20_000);
});
