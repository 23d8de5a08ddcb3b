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

  describe('frames on a UART (an Uno behind its USB bridge): each frame counted by its own bytes', () => {
    // 10-byte PINGs and 16-byte PONGs at 250 000 baud, 40 µs a byte. The device stamps
    // the ping at its last byte and the pong at its first; the author reads the pong
    // at its last byte. Besides the wire, each way waits a USB frame (0–1 ms).
    const BYTE_US = 40;
    const PING_BYTES = 10;
    const PONG_BYTES = 16;
    function uartRun(counted: boolean, seed: number) {
      const rand = seededRandom(seed);
      const ppm = 120;
      const dev = (a: number) => 7_000_000 + a * (1 + ppm * 1e-6);
      const sync = new ClockSync();
      const errors: number[] = [];
      for (let a = 0; a < 120e6; a += 10_000) {
        const a1 = a + rand() * 1000;
        const arrive = Math.ceil(a1 / 1000) * 1000 + 50 + rand() * 100 + PING_BYTES * BYTE_US;
        const reply = arrive + 20 + rand() * 2000;
        const back = Math.ceil((reply + PONG_BYTES * BYTE_US) / 1000) * 1000 + 50 + rand() * 100;
        sync.add({
          authorSend: a1,
          authorReceive: back,
          deviceReceive: Math.floor(dev(arrive)),
          deviceReply: Math.floor(dev(reply)),
          ...(counted ? { pingOnWire_us: PING_BYTES * BYTE_US, pongOnWire_us: PONG_BYTES * BYTE_US } : {}),
        });
        if (a > 60e6) errors.push(sync.clock!.toDeviceExact(a + 20_000) - dev(a + 20_000));
      }
      errors.sort((x, y) => x - y);
      return { sync, median: errors[errors.length >> 1], worst: Math.max(-errors[0], errors[errors.length - 1]) };
    }

    it('uncounted, the model is off by half the frames’ difference, (10 − 16)·40/2 = −120 µs', () => {
      const { median } = uartRun(false, 5);
      expect(median).toBeGreaterThan(-125);
      expect(median).toBeLessThan(-115);
    });

    it('counted, the error is that of a symmetric link (a few µs), and the round trip still includes the wire', () => {
      for (const seed of [5, 6, 7]) {
        const { sync, median, worst } = uartRun(true, seed);
        expect(Math.abs(median)).toBeLessThan(3);
        expect(worst).toBeLessThan(10);
        // 26 bytes on the wire (1 040 µs) are part of every round trip.
        expect(sync.rtt).toBeGreaterThan(26 * BYTE_US);
      }
    });

    it('a link without a UART (wire times 0 or absent) gives the same model as before', () => {
      const stamps = { authorSend: 1000, authorReceive: 3000, deviceReceive: 501_000, deviceReply: 501_500 };
      const plain = new ClockSync();
      const zero = new ClockSync();
      plain.add(stamps);
      zero.add({ ...stamps, pingOnWire_us: 0, pongOnWire_us: 0 });
      expect(zero.clock!.toDeviceExact(10_000)).toBe(plain.clock!.toDeviceExact(10_000));
      expect(zero.rtt).toBe(plain.rtt);
    });
  });
});

describe('ClockSync on a link that corrupts frames', () => {
  /**
   * Pings every 4 ms (a session's first two minutes) for 8 s on a clean link, except
   * that each exchange that comes alone into the rate fit's last slice of 64 (the
   * 65th, the 129th...) is a resent ping: its first copy was corrupted, the copy
   * that came through left 4 ms later, and the stamp stays the first copy's (the
   * exchange looks 4 ms slow going up, as in the session). Returns the largest move of the model's
   * prediction 20 ms ahead at such an exchange, after the first second: what a
   * segment timed just before it and run just after it would be off by.
   */
  function worstMoveAtALoneSlowExchange(seed: number): number {
    const rand = seededRandom(seed);
    const dev = (a: number) => 9_000_000 + a * (1 - 60e-6);
    const sync = new ClockSync();
    let worst = 0;
    for (let a = 0; a < 8e6; a += 4000 * (0.75 + 0.5 * rand())) {
      const resent = sync.samples % 64 === 0 && sync.samples > 0;
      const e = exchange(rand, a + (resent ? 4000 : 0), dev, [150, 1250], [250, 500]);
      const before = sync.clock?.toDeviceExact(e.authorReceive + 20_000);
      sync.add({ ...e, authorSend: a });
      const after = sync.clock!.toDeviceExact(e.authorReceive + 20_000);
      if (resent && a > 1e6) worst = Math.max(worst, Math.abs(after - before!));
    }
    return worst;
  }

  it('a resent ping alone in the rate fit’s last slice does not swing the rate (the model moves < 15 µs)', () => {
    // When a slice could hold one exchange, its "fast edge" was that exchange whatever
    // its delay: a ping 4 ms slow pulled the least-squares rate, and the refit moved
    // the model by tens of µs (fault matrix, corruption 1e-2: 70 µs, back 100 ms later).
    // Here: 27–88 µs before, 1–10 µs since (the refits' ordinary moves).
    const moves = [1, 2, 3, 4].map(worstMoveAtALoneSlowExchange);
    for (const m of moves) expect(m).toBeLessThan(15);
  });
});

describe('ClockSync round trips (Karn’s rule)', () => {
  it('a resent ping’s exchange serves the fit but not the round trips: its wait for the resend is not the link’s', () => {
    const rand = seededRandom(9);
    const dev = (a: number) => 1e6 + a;
    const karn = new ClockSync();
    const naive = new ClockSync();
    for (let a = 0; a < 2e6; a += 4000) {
      // Every fifth ping was resent 4 ms after its first copy, which the stamp keeps.
      const resent = (a / 4000) % 5 === 4;
      const e = exchange(rand, a + (resent ? 4000 : 0), dev, [150, 1250], [250, 500]);
      karn.add({ ...e, authorSend: a, resent });
      naive.add({ ...e, authorSend: a });
    }
    // Round trips here: up to 1.25 + 2 (the reply's wait, not counted) + 0.5 ms + a USB frame.
    expect(karn.rttHigh).toBeLessThan(3000);
    expect(naive.rttHigh).toBeGreaterThan(5000);
    expect(karn.samples).toBe(naive.samples);
    expect(karn.clock!.toDeviceExact(2e6)).toBe(naive.clock!.toDeviceExact(2e6));
  });
});

describe('ClockSync slews its refits', () => {
  /**
   * Pings every 4 ms on a clean link for 4 s; at 2.2 s one exchange's ping comes
   * 120 µs faster than the link's floor (its up point 120 µs below every other):
   * the fit's lower envelope, and with it the offset, drops by about 60 µs at once,
   * as the young model of the fault matrix's corruption case did (light painter,
   * seed 15: 62 µs in one refit, 2.2 s after begin()). Returns the largest move of
   * the model's prediction 20 ms ahead from one exchange to the next after the first
   * second (what a segment timed before a refit and run after it is off by), and the
   * model's prediction at the end.
   */
  function movesAroundAFastExchange(maxRefitMove_us: number) {
    const rand = seededRandom(11);
    const dev = (a: number) => 3_000_000 + a * (1 + 40e-6);
    const sync = new ClockSync({ maxRefitMove_us });
    let worst = 0;
    let fastDone = false;
    for (let a = 0; a < 4e6; a += 4000 * (0.75 + 0.5 * rand())) {
      const e = exchange(rand, a, dev, [150, 1250], [250, 500]);
      if (!fastDone && a > 2.2e6) {
        fastDone = true;
        e.deviceReceive = Math.floor(dev(a + 30)); // up in 30 µs, below the floor of 150
      }
      const before = sync.clock?.toDeviceExact(e.authorReceive + 20_000);
      sync.add(e);
      const after = sync.clock!.toDeviceExact(e.authorReceive + 20_000);
      if (a > 1e6) worst = Math.max(worst, Math.abs(after - before!));
    }
    return { worst, end: sync.clock!.toDeviceExact(4.02e6) };
  }

  it('one refit moves the model by at most maxRefitMove_us (10 µs) plus the rate change’s share, and the rest follows', () => {
    const unslewed = movesAroundAFastExchange(Infinity);
    const slewed = movesAroundAFastExchange(10);
    // Unslewed, the fast exchange moves the model by tens of µs in one refit.
    expect(unslewed.worst).toBeGreaterThan(40);
    // Slewed: 10 µs at the refit's exchange, and the new rate's share 20 ms on
    // (a few ppm × 20 ms, well under 1 µs), within REFIT_US (25 µs) of the fault checks.
    expect(slewed.worst).toBeLessThan(11);
    // The rest is applied over the next refits (10 µs each, every 100 ms while the
    // window is young): 1.8 s later the two models agree.
    expect(Math.abs(slewed.end - unslewed.end)).toBeLessThan(0.5);
  });
});
