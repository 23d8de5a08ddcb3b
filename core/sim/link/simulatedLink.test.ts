import { describe, expect, it } from 'vitest';
import { VirtualScheduler } from '../../time/virtualScheduler.ts';
import { seededRandom } from '../../random.ts';
import type { LinkOverrides } from './linkConfig.ts';
import { SimulatedLink } from './simulatedLink.ts';

interface Arrival {
  at: number;
  bytes: Uint8Array;
}

/** A link with the author's readable drained into `toAuthor` and device arrivals into `toDevice`. */
function harness(overrides: LinkOverrides) {
  const s = new VirtualScheduler();
  const sim = new SimulatedLink(s, 'test', overrides);
  const toDevice: Arrival[] = [];
  const toAuthor: Arrival[] = [];
  sim.device.onReceive((bytes, at) => {
    expect(at).toBe(s.now());
    toDevice.push({ at, bytes });
  });
  void (async () => {
    const reader = sim.link.readable.getReader();
    for (;;) {
      const { value, done } = await reader.read();
      if (done) return;
      toAuthor.push({ at: s.now(), bytes: value });
    }
  })();
  const writer = sim.link.writable.getWriter();
  /** The author writes `bytes` at author time `at`. */
  const authorWrites = (at: number, bytes: Uint8Array) => s.at(at, () => void writer.write(bytes));
  return { s, sim, toDevice, toAuthor, authorWrites };
}

const concat = (arrivals: Arrival[]) => Uint8Array.from(arrivals.flatMap((a) => [...a.bytes]));
const mean = (xs: number[]) => xs.reduce((a, b) => a + b, 0) / xs.length;
const std = (xs: number[]) => Math.sqrt(mean(xs.map((x) => (x - mean(xs)) ** 2)));

describe('SimulatedLink timing', () => {
  it('sends author bytes at the next 1 ms USB frame, then adds the base delay', async () => {
    const h = harness({ toDevice: { baseDelay_us: 120, jitterMin_us: 0, jitterMax_us: 0 } });
    const random = seededRandom(7);
    const writes: number[] = [];
    for (let k = 0; k < 200; k++) writes.push(k * 5000 + Math.floor(random() * 5000));
    writes.forEach((t, k) => h.authorWrites(t, Uint8Array.of(k)));
    await h.s.runUntil(1_100_000);
    expect(h.toDevice.map((a) => a.bytes[0])).toEqual(writes.map((_, k) => k));
    h.toDevice.forEach((a, k) => {
      const frame = a.at - 120;
      expect(frame % 1000).toBe(0); // on a frame boundary
      expect(frame).toBeGreaterThan(writes[k]); // strictly after the write
      expect(frame - writes[k]).toBeLessThanOrEqual(1000); // the very next frame
    });
    // Frame waits are spread over (0, 1000]: mean about 500 µs.
    expect(mean(h.toDevice.map((a, k) => a.at - 120 - writes[k]))).toBeGreaterThan(400);
    expect(mean(h.toDevice.map((a, k) => a.at - 120 - writes[k]))).toBeLessThan(600);
  });

  it('draws jitter uniformly in [min, max], independently per direction', async () => {
    const h = harness({
      toDevice: { baseDelay_us: 100, jitterMin_us: 50, jitterMax_us: 350 },
      toAuthor: { baseDelay_us: 400, jitterMin_us: 0, jitterMax_us: 1000 },
    });
    const n = 600;
    // Writes on frame boundaries + 1 µs, 5 ms apart: the frame is the next boundary, no bunching.
    for (let k = 0; k < n; k++) {
      h.authorWrites(k * 5000 + 1, Uint8Array.of(k & 0xff));
      h.s.at(k * 5000 + 1, () => h.sim.device.send(Uint8Array.of(k & 0xff), h.s.now()));
    }
    await h.s.runUntil(n * 5000 + 10_000);
    const jitterDown = h.toDevice.map((a, k) => a.at - (k * 5000 + 1000) - 100);
    const jitterUp = h.toAuthor.map((a, k) => a.at - (k * 5000 + 1000) - 400);
    expect(jitterDown.length).toBe(n);
    expect(jitterUp.length).toBe(n);
    expect(Math.min(...jitterDown)).toBeGreaterThanOrEqual(50);
    expect(Math.max(...jitterDown)).toBeLessThanOrEqual(350);
    // Uniform on [a, b]: mean (a+b)/2, standard deviation (b−a)/√12; n = 600 gives ~3 % error at 3σ.
    expect(mean(jitterDown)).toBeCloseTo(200, -1.3);
    expect(std(jitterDown)).toBeCloseTo(300 / Math.sqrt(12), -1);
    expect(Math.min(...jitterUp)).toBeGreaterThanOrEqual(0);
    expect(Math.max(...jitterUp)).toBeLessThanOrEqual(1000);
    expect(Math.abs(mean(jitterUp) - 500)).toBeLessThan(40);
    expect(Math.abs(std(jitterUp) - 1000 / Math.sqrt(12))).toBeLessThan(25);
    const r = h.sim.report();
    expect(r.toDevice.latencyMin_us).toBeGreaterThanOrEqual(999 + 100 + 50);
    expect(r.toAuthor.latencyMax_us).toBeLessThanOrEqual(999 + 400 + 1000);
  });

  it('keeps bytes in order under heavy jitter, bunching rather than reordering', async () => {
    const h = harness({ toAuthor: { baseDelay_us: 0, jitterMin_us: 0, jitterMax_us: 8000 } });
    const sent: number[] = [];
    for (let k = 0; k < 400; k++) {
      sent.push(k & 0xff);
      h.s.at(k * 300, () => h.sim.device.send(Uint8Array.of(k & 0xff), h.s.now()));
    }
    await h.s.runUntil(200_000);
    expect([...concat(h.toAuthor)]).toEqual(sent);
    for (let i = 1; i < h.toAuthor.length; i++) expect(h.toAuthor[i].at).toBeGreaterThanOrEqual(h.toAuthor[i - 1].at);
  });

  it('carries at most bytesPerFrame per frame, spilling big writes into later frames', async () => {
    const h = harness({ toDevice: { baseDelay_us: 0, jitterMin_us: 0, jitterMax_us: 0 } });
    const big = Uint8Array.from({ length: 5000 }, (_, i) => (i * 7) & 0xff);
    h.authorWrites(10, big);
    await h.s.runUntil(20_000);
    expect(concat(h.toDevice)).toEqual(big);
    // 1216 bytes per frame: frames at 1, 2, 3, 4 ms carry 1216 each, 5 ms the last 136.
    expect(h.toDevice.map((a) => [a.at, a.bytes.length])).toEqual([
      [1000, 1216],
      [2000, 1216],
      [3000, 1216],
      [4000, 1216],
      [5000, 136],
    ]);
    expect(h.sim.report().toDevice.framesUsed).toBe(5);
    expect(h.sim.report().toDevice.packetsSent).toBe(Math.ceil(1216 / 64) * 4 + Math.ceil(136 / 64));
  });
});

describe('SimulatedLink faults', () => {
  it('corrupts bytes at the configured rate and counts exactly the bytes it changed', async () => {
    const h = harness({ toDevice: { corruptionProbability: 0.01 } });
    const sent = Uint8Array.from({ length: 60_000 }, (_, i) => (i * 13) & 0xff);
    for (let k = 0; k < 60; k++) h.authorWrites(k * 2000, sent.subarray(k * 1000, (k + 1) * 1000));
    await h.s.runUntil(200_000);
    const got = concat(h.toDevice);
    expect(got.length).toBe(sent.length);
    let changed = 0;
    for (let i = 0; i < got.length; i++) if (got[i] !== sent[i]) changed++;
    const r = h.sim.report().toDevice;
    expect(r.bytesCorrupted).toBe(changed);
    // Binomial(60000, 0.01): mean 600, σ ≈ 24.4.
    expect(Math.abs(changed - 600)).toBeLessThan(100);
    expect(h.sim.report().toAuthor.bytesCorrupted).toBe(0);
  });

  it('loses whole USB packets at the configured rate', async () => {
    const h = harness({ toAuthor: { lossProbability: 0.1 } });
    // 2000 writes of 64 bytes, each its own packet: byte value = packet index (mod 256) in every position.
    for (let k = 0; k < 2000; k++) h.s.at(k * 1000 + 500, () => h.sim.device.send(new Uint8Array(64).fill(k & 0xff), h.s.now()));
    await h.s.runUntil(2_010_000);
    const r = h.sim.report().toAuthor;
    expect(r.packetsSent).toBe(2000);
    // Binomial(2000, 0.1): mean 200, σ ≈ 13.4.
    expect(Math.abs(r.packetsLost - 200)).toBeLessThan(60);
    expect(r.bytesLost).toBe(64 * r.packetsLost);
    expect(r.bytesDelivered).toBe(64 * (2000 - r.packetsLost));
    const got = concat(h.toAuthor);
    expect(got.length).toBe(r.bytesDelivered);
    // What arrives is whole packets, in order.
    for (let p = 0; p < got.length; p += 64) expect(new Set(got.subarray(p, p + 64)).size).toBe(1);
  });

  it('passes nothing either way after a cut at a configured time, counting what it dropped', async () => {
    const h = harness({ cutAt_us: 50_000, toDevice: { jitterMin_us: 0, jitterMax_us: 0 }, toAuthor: { jitterMin_us: 0, jitterMax_us: 0 } });
    for (let k = 0; k < 100; k++) {
      h.authorWrites(k * 1000 + 100, Uint8Array.of(1, 2));
      h.s.at(k * 1000 + 100, () => h.sim.device.send(Uint8Array.of(3), h.s.now()));
    }
    await h.s.runUntil(200_000);
    expect(h.toDevice.every((a) => a.at < 50_000)).toBe(true);
    expect(h.toAuthor.every((a) => a.at < 50_000)).toBe(true);
    const r = h.sim.report();
    // Writes at 100..48100 µs arrive by 49.15 ms (toDevice) or 49.25 ms (toAuthor); the one at 49100 µs is due after the cut.
    expect(h.toDevice.length).toBe(49);
    expect(h.toAuthor.length).toBe(49);
    expect(r.toDevice.bytesCut).toBe(2 * 51);
    expect(r.toAuthor.bytesCut).toBe(51);
    expect(r.toDevice.bytesDelivered + r.toDevice.bytesCut).toBe(r.toDevice.bytesWritten);
  });

  it('cuts on command, and restore() lets new bytes through again', async () => {
    const h = harness({});
    for (let k = 0; k < 30; k++) h.authorWrites(k * 1000, Uint8Array.of(k));
    h.s.at(10_500, () => h.sim.cut());
    h.s.at(20_500, () => h.sim.restore());
    await h.s.runUntil(40_000);
    const values = h.toDevice.map((a) => a.bytes[0]);
    // Written at 9 ms: due about 10.2 ms, before the cut. Written at 10 ms: due after it. From 21 ms on: passes again.
    expect(values).toEqual([...Array.from({ length: 10 }, (_, k) => k), ...Array.from({ length: 9 }, (_, k) => 21 + k)]);
    expect(h.sim.isCut()).toBe(false);
  });

  it('lets a test change fault rates mid-run', async () => {
    const h = harness({});
    for (let k = 0; k < 40; k++) h.authorWrites(k * 1000 + 10, new Uint8Array(32).fill(0x55));
    h.s.at(20_000, () => h.sim.configure('toDevice', { corruptionProbability: 1 }));
    await h.s.runUntil(50_000);
    const got = concat(h.toDevice);
    expect([...got.subarray(0, 20 * 32)].every((b) => b === 0x55)).toBe(true);
    expect([...got.subarray(20 * 32)].every((b) => b !== 0x55)).toBe(true);
    expect(h.sim.report().toDevice.bytesCorrupted).toBe(20 * 32);
  });
});

describe('SimulatedLink determinism', () => {
  async function run(seed: number) {
    const h = harness({ seed, toDevice: { corruptionProbability: 0.05, lossProbability: 0.05 }, toAuthor: { jitterMax_us: 900 } });
    for (let k = 0; k < 200; k++) {
      h.authorWrites(k * 700, Uint8Array.from({ length: 40 }, (_, i) => (i + k) & 0xff));
      h.s.at(k * 700 + 3, () => h.sim.device.send(Uint8Array.of(k & 0xff, 9), h.s.now()));
    }
    await h.s.runUntil(200_000);
    return {
      toDevice: JSON.stringify(h.toDevice.map((a) => [a.at, [...a.bytes]])),
      toAuthor: JSON.stringify(h.toAuthor.map((a) => [a.at, [...a.bytes]])),
      report: JSON.stringify(h.sim.report()),
    };
  }

  it('gives the same bytes at the same times for the same seed, and different ones for another, in each direction', async () => {
    const a = await run(42);
    expect(await run(42)).toEqual(a);
    const b = await run(43);
    expect(b.toDevice).not.toBe(a.toDevice);
    expect(b.toAuthor).not.toBe(a.toAuthor);
  });
});
