/**
 * The fake boards' end of a port keeps the bytes' times: a chunk enters its
 * board's link at the time the opener wrote it (on the boards' paced clock),
 * not when the boards' process read it; one that came after its time goes in at
 * once and is counted late; the board's replies go back over the socket. Over a
 * real WebSocket on localhost (the `ws` package), as the WebSerial spec runs it.
 */
import { afterEach, describe, expect, it } from 'vitest';
import { WebSocket, WebSocketServer } from 'ws';
import { PacedScheduler } from '../../core/index.ts';
import type { Link } from '../../core/net/link.ts';
import { connectBoard, wakeAfterIo, type BoardTraffic } from './fakeBoardLink.ts';
import { decodeStampedChunk, encodeStampedChunk } from './fakePortStreams.ts';

describe('stamped chunks', () => {
  it('carry their bytes and the time they were written', () => {
    const chunk = { bytes: new Uint8Array([0, 1, 2, 255]), sentAt_ms: 1_700_000_000_123.4567 };
    expect(decodeStampedChunk(encodeStampedChunk(chunk))).toEqual(chunk);
  });

  it('say so when a frame is too short to hold a stamp', () => {
    expect(() => decodeStampedChunk(new Uint8Array(5))).toThrow(/5 bytes, shorter than its 8-byte time stamp/);
  });
});

/** A board's link that records the virtual time each write reached it, and lets the test say things back. */
function recordingLink(scheduler: PacedScheduler) {
  const arrivals: Array<{ bytes: number[]; at_us: number }> = [];
  let say!: (bytes: Uint8Array) => void;
  const link: Link = {
    writable: new WritableStream({ write: (bytes) => void arrivals.push({ bytes: [...bytes], at_us: scheduler.now() }) }),
    readable: new ReadableStream({ start: (c) => void (say = (b) => c.enqueue(b)) }),
  };
  return { link, arrivals, say: (b: Uint8Array) => say(b) };
}

describe('a fake board behind a WebSocket', () => {
  const cleanup: Array<() => void> = [];
  afterEach(() => {
    for (const c of cleanup.splice(0)) c();
  });

  async function boardAndOpener() {
    const scheduler = new PacedScheduler({ wake: wakeAfterIo() });
    const server = new WebSocketServer({ host: '127.0.0.1', port: 0 });
    await new Promise((r) => server.once('listening', r));
    const board = recordingLink(scheduler);
    const traffic = new Promise<BoardTraffic>((resolve) => server.once('connection', (socket) => resolve(connectBoard(board.link, socket, scheduler))));
    const { port } = server.address() as { port: number };
    const opener = new WebSocket(`ws://127.0.0.1:${port}`);
    await new Promise((r) => opener.once('open', r));
    cleanup.push(() => {
      scheduler.stop();
      opener.close();
      server.close();
    });
    // Keep the boards' clock moving, as the devices' loops do.
    const tick = () => scheduler.at(scheduler.now() + 1000, tick);
    tick();
    return { scheduler, board, opener, traffic: await traffic };
  }

  const epochNow_ms = () => performance.timeOrigin + performance.now();

  it("delivers a chunk at its writer's time, not when the process read it", async () => {
    const { scheduler, board, opener, traffic } = await boardAndOpener();
    // Written "30 ms from now" (as if the opener's clock were ahead): due then, not on arrival.
    const sentAt_ms = epochNow_ms() + 30;
    opener.send(encodeStampedChunk({ bytes: new Uint8Array([7, 8]), sentAt_ms }));
    await expect.poll(() => board.arrivals.length, { timeout: 2000 }).toBe(1);
    const due_us = scheduler.virtualTimeAtWall((sentAt_ms - performance.timeOrigin) * 1000);
    expect(board.arrivals[0]).toEqual({ bytes: [7, 8], at_us: due_us });
    expect(traffic).toMatchObject({ chunks: 1, late: 0 });
  });

  it('counts a chunk that came after its time, and delivers it at once', async () => {
    const { scheduler, board, opener, traffic } = await boardAndOpener();
    await new Promise((r) => setTimeout(r, 60));
    // Written 500 ms ago (held back on its way): the simulation has long passed its time.
    const sentAt_ms = epochNow_ms() - 500;
    opener.send(encodeStampedChunk({ bytes: new Uint8Array([1]), sentAt_ms }));
    await expect.poll(() => board.arrivals.length, { timeout: 2000 }).toBe(1);
    const due_us = scheduler.virtualTimeAtWall((sentAt_ms - performance.timeOrigin) * 1000);
    expect(traffic.late).toBe(1);
    // How late: how far the simulation had run past its time when it came (the wall less the
    // boards' clock's lag behind it, under a few ms here).
    expect(traffic.worstLate_us).toBeGreaterThan(250_000);
    // At once: at the simulation's time when it came, not at its own time in the past.
    expect(board.arrivals[0].at_us).toBeGreaterThanOrEqual(due_us + traffic.worstLate_us);
    expect(board.arrivals[0].at_us).toBeLessThan(due_us + traffic.worstLate_us + 5_000);
  });

  it("sends the board's bytes back", async () => {
    const { board, opener, traffic } = await boardAndOpener();
    const got = new Promise<number[]>((r) => opener.once('message', (data: Buffer) => r([...data])));
    board.say(new Uint8Array([9, 10, 11]));
    expect(await got).toEqual([9, 10, 11]);
    expect(traffic.replies).toBe(1);
  });
});
