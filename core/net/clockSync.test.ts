import { describe, expect, it } from 'vitest';
import { ClockSync } from './clockSync.ts';
import { U32 } from './clockMap.ts';
import { seededRandom } from '../random.ts';

/**
 * A synthetic link and device clock, independent of the simulator: the device
 * clock runs at (1 + ppm) from an offset and wraps at 2³²; each direction's delay
 * is a floor plus uniform jitter, and device→author data waits for the next 1 ms
 * USB frame.
 */
function exchange(
  rand: () => number,
  a1: number,
  dev: (a: number) => number,
  up: [number, number],
  down: [number, number],
) {
  const arrive = a1 + up[0] + rand() * (up[1] - up[0]);
  const reply = arrive + 20 + rand() * 2000; // PING replyAfter: 0–2 ms, drawn by the author
  let back = reply + down[0] + rand() * (down[1] - down[0]);
  back = Math.ceil(back / 1000) * 1000; // the host polls once per USB frame
  const wrap = (x: number) => ((Math.floor(x) % U32) + U32) % U32;
  return { authorSend: a1, authorReceive: back, deviceReceive: wrap(dev(arrive)), deviceReply: wrap(dev(reply)) };
}

function run(ppm: number, offset: number, seconds: number, seed: number, up: [number, number], down: [number, number]) {
  const rand = seededRandom(seed);
  const dev = (a: number) => offset + a * (1 + ppm * 1e-6);
  const sync = new ClockSync();
  const errors: number[] = [];
  for (let a = 0; a < seconds * 1e6; a += 10_000) {
    sync.add(exchange(rand, a + rand() * 1000, dev, up, down));
    if (a > seconds * 0.5e6) {
      // Error of the model's prediction 20 ms ahead, as when timing a segment.
      const t = a + 20_000;
      const predicted = sync.clock!.toDeviceExact(t);
      errors.push(Math.abs(predicted - dev(t)));
    }
  }
  errors.sort((x, y) => x - y);
  return { sync, p99: errors[Math.floor(errors.length * 0.99)], max: errors[errors.length - 1], final: errors[errors.length - 1] };
}

describe('ClockSync', () => {
  it('tracks a 200 ppm fast clock through asymmetric jitter (the last 5 of 10 minutes)', () => {
    const { sync, p99, max } = run(200, 123_456_789, 600, 1, [100, 1500], [100, 500]);
    expect(Math.abs(sync.clock!.rate - 1.0002)).toBeLessThan(0.02e-6);
    expect(p99).toBeLessThan(10);
    expect(max).toBeLessThan(15);
    expect(sync.rtt).toBeGreaterThan(200);
    expect(sync.errorEstimate_us).toBeLessThan(20);
  });

  it('tracks a slow clock across the 32-bit wrap', () => {
    // Starts 5 minutes before the wrap and runs 5 minutes past it.
    const { sync, p99 } = run(-180, U32 - 300e6 * (1 - 180e-6), 600, 2, [300, 1200], [300, 1200]);
    expect(Math.abs(sync.clock!.rate - (1 - 180e-6))).toBeLessThan(0.02e-6);
    // A mistaken unwrap would be off by 2³² µs; this jitter (0.3–1.2 ms both ways) converges a little slower.
    expect(p99).toBeLessThan(15);
  });

  it('gives a usable model within a second of start-up', () => {
    const rand = seededRandom(3);
    const dev = (a: number) => 5e6 + a * (1 + 100e-6);
    const sync = new ClockSync();
    for (let a = 0; a < 1e6; a += 50_000) sync.add(exchange(rand, a, dev, [100, 1500], [100, 500]));
    expect(Math.abs(sync.clock!.toDeviceExact(1.02e6) - dev(1.02e6))).toBeLessThan(300);
  });
});
