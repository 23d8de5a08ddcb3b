/**
 * npm run bench -- sync
 *
 * Clock synchronisation over one simulated hour, real firmware in wasm on simulated
 * USB full-speed links, in virtual time:
 *   - the light painter's three boards, each crystal drawn within ±200 ppm (seeded);
 *   - each link: asymmetric one-way delays of 0.1–1.5 ms (SYNC_LINK=spec, the
 *     default) or much more (SYNC_LINK=harsh), see LINKS below;
 *   - every second, the error of each device's clock model predicting its clock
 *     10 ms ahead (as when timing a segment) against the simulator's true clock.
 * p99ErrorUs and maxErrorUs cover the whole hour after begin() (which syncs for 2 s).
 * oneShotMaxErrorUs is the paper's method under the same conditions: the offset
 * from the average half round trip of the first 20 pings, set once, rate taken as 1.
 * Targets: p99 ≤ 10 µs, max ≤ 50 µs, on every seed.
 *
 * SEED=n runs one seed (default 7). SYNC_SEEDS=1-20 (or 1,4,9 or 3-5,9) runs each
 * seed in turn (a seed draws the crystals' offsets and rates and every link's
 * jitter) and prints, besides each seed's figures, the worst of them:
 *   worstP99Us / worstP99Seed: the largest per-seed p99ErrorUs, and its seed;
 *   worstMaxUs / worstMaxSeed: the largest per-seed maxErrorUs, and its seed.
 * Each seed's p99 and max are over its own 3 devices × ~3600 one-second samples.
 *
 * Figures (spec link), p99 / max in µs per seed. Before: the rate by least squares
 * over one extreme per slice (commit b080803). After: through the fastest 5 % of
 * each slice (core/net/clockSync.ts). Seeds 15–20 "after" were run by this bench
 * (SYNC_SEEDS=15,16 / 17,18 / 19,20); seeds 1–14 by replaying each seed's recorded
 * ping exchanges through the new ClockSync (the estimator does not change the
 * exchanges; that replay reproduced this bench's old figures on seed 1 exactly).
 *   seed  before          after          seed  after
 *   1     12.56 / 29.71   5.90 / 17.01   11    8.45 / 33.17
 *   2      7.10 / 19.35   5.95 / 23.71   12    5.03 / 27.65
 *   3      8.88 / 39.82   4.83 / 39.42   13    6.62 / 45.14
 *   4      8.79 / 51.09   5.56 / 39.47   14    7.19 / 19.35
 *   5                     6.40 / 40.77   15    6.59 / 27.95
 *   6                     4.75 / 26.49   16    7.21 / 17.48
 *   7                     5.71 / 21.12   17    6.21 / 18.83
 *   8                     5.57 / 17.97   18    5.62 / 49.31
 *   9     10.23 (p99)     5.59 / 25.27   19    5.41 / 17.54
 *   10    51.72 (max)     5.76 / 22.38   20    6.03 / 29.28
 * Worst after: p99 8.45 µs (seed 11), max 49.31 µs (seed 18, at 3–10 s after begin():
 * the first seconds' few exchanges, not the rate, set the max; 0.7 µs of margin).
 * Denser pings (1 ms in begin()'s burst, 2 ms while young) were tried and made the
 * p99 worse (15–19 µs on seeds 1, 6, 11, 16), so the ping schedule is unchanged.
 *
 * After the rate fit's last slice took the remainder (no slice shorter than 64
 * exchanges; clockSync.ts), all 20 seeds run by this bench at nice 12 on the shared
 * machine, in three processes (SYNC_SEEDS=1-20 stopped after seed 7; 18,11,12,10,9,8;
 * 13-20, whose seed 18 gave the same figures):
 *   seed  p99 / max      seed  p99 / max      seed  p99 / max      seed  p99 / max
 *   1     5.84 / 17.38   6     4.72 / 26.49   11    8.40 / 33.73   16    7.30 / 22.86
 *   2     6.09 / 23.57   7     5.40 / 24.88   12    5.06 / 28.14   17    6.16 / 21.01
 *   3     4.80 / 42.64   8     5.23 / 21.11   13    6.83 / 37.50   18    5.66 / 49.31
 *   4     5.61 / 40.94   9     5.60 / 26.10   14    6.96 / 20.31   19    5.36 / 17.79
 *   5     6.29 / 43.40   10    5.67 / 22.93   15    6.69 / 28.88   20    6.02 / 29.28
 * Worst: p99 8.40 µs (seed 11), max 49.31 µs (seed 18, in its first 10 s, as before).
 *
 * After the refits were slewed (at most 10 µs of offset a refit; clockSync.ts,
 * "Slewing"), all 20 seeds in two processes (SYNC_SEEDS=18,11 at nice 0, then
 * 1-10,12-17,19,20 at nice 10): every seed as in the table above except
 *   seed 11: 8.40 / 33.39 (was 33.73)   seed 13: 6.83 / 42.58 (was 37.50)
 *   seed 17: 6.14 / 21.01 (p99 was 6.16)
 * Worst: p99 8.40 µs (seed 11), max 49.31 µs (seed 18), unchanged.
 */
import { createMAXL } from '../core/index.ts';
import { VirtualScheduler } from '../core/time/virtualScheduler.ts';
import { createSimulatedMachine } from '../core/sim/machine.ts';
import { nodeWasmLoader } from '../core/sim/device/nodeWasmLoader.ts';
import { lightPainter } from '../core/sim/presets/index.ts';
import { seededRandom } from '../core/random.ts';
import { u32Diff } from '../core/net/clockMap.ts';
import { seedListEnv } from './args.mjs';

const HOUR_US = Number(process.env.SYNC_SECONDS ?? 3600) * 1e6;
/**
 * The links. Each one-way delay is a fixed base, plus the wait for the next 1 ms
 * USB frame (0–1 ms, the simulated link's own), plus a uniform jitter.
 *  - spec (default): the conditions, one-way delays of 0.1–1.5 ms in all,
 *    asymmetric: author→device 0.1 + 0–1 + 0–0.4 ms, device→author 0.1 + 0–1 + 0–0.1 ms.
 *  - harsh: the jitter of 0.1–1.5 ms (author→device) and 0.1–0.6 ms (device→author)
 *    on top of the USB frames and a 0.2 ms base: one-way delays of 0.3–2.7 ms and 0.3–1.8 ms.
 */
const LINKS = {
  spec: {
    toDevice: { baseDelay_us: 100, jitterMin_us: 0, jitterMax_us: 400 },
    toAuthor: { baseDelay_us: 100, jitterMin_us: 0, jitterMax_us: 100 },
  },
  harsh: {
    toDevice: { baseDelay_us: 200, jitterMin_us: 100, jitterMax_us: 1500 },
    toAuthor: { baseDelay_us: 200, jitterMin_us: 100, jitterMax_us: 600 },
  },
};
const PROFILE = (process.env.SYNC_LINK ?? 'spec') as keyof typeof LINKS;
if (!(PROFILE in LINKS)) throw new Error(`SYNC_LINK must be one of ${Object.keys(LINKS).join(', ')}`);
/** Seeds to run: SYNC_SEEDS ("1-20", "1,4,9", "3-5,9"), else SEED (default 7). */
function seedList(): number[] {
  return seedListEnv('SYNC_SEEDS', [Number(process.env.SEED ?? 7)]);
}

/** One simulated hour on one seed: the error figures. */
async function runSeed(SEED: number) {
  const random = seededRandom(SEED);
  const preset = lightPainter();
  const scheduler = new VirtualScheduler();
  const clocks: Record<string, { offset_us: number; ppm: number }> = {};
  const links: Record<string, object> = {};
  for (const d of preset.devices) {
    clocks[d.name] = { offset_us: Math.floor(random() * 4e9), ppm: (random() * 2 - 1) * 200 };
    links[d.name] = LINKS[PROFILE];
  }
  const started = performance.now();
  const sim = await createSimulatedMachine(preset, scheduler, { seed: SEED, loader: nodeWasmLoader(), clocks, links });
  // SYNC_PING_MS: the steady ping period to try (default: the session's).
  const pingEvery_us = process.env.SYNC_PING_MS ? Number(process.env.SYNC_PING_MS) * 1000 : undefined;
  // SYNC_YOUNG_S: how long a new session pings at its young period (default: the session's).
  const youngFor_us = process.env.SYNC_YOUNG_S ? Number(process.env.SYNC_YOUNG_S) * 1e6 : undefined;
  const session = { ...(pingEvery_us ? { pingEvery_us } : {}), ...(youngFor_us ? { youngFor_us } : {}) };
  const maxl = createMAXL(sim.config, { links: Object.values(sim.links), scheduler, session });
  const ready = maxl.begin();
  await scheduler.runWhile(() => true, 2_500_000);
  await ready;

  type Session = { info: { name: string }; clock: { clock: { toDeviceExact(t: number): number } } };
  const sessions = (maxl as unknown as { runtime: { sessions: Session[] } }).runtime.sessions;

  // The paper's one-shot sync, emulated from the same links: average half round trip.
  const oneShot: Record<string, number> = {};
  {
    for (const s of sessions) {
      const c = (s.clock as unknown as { a1: number[]; a2: number[]; d1: number[]; d2: number[] });
      const n = Math.min(20, c.a1.length);
      let sum = 0;
      for (let i = 0; i < n; i++) {
        // Set "device = author + half RTT later": offset = d(mid) − a(mid), symmetric assumption.
        sum += (c.d1[i] + c.d2[i]) / 2 - (c.a1[i] + c.a2[i]) / 2;
      }
      oneShot[s.info.name] = sum / n;
    }
  }

  const errors: number[] = [];
  const bands: Record<string, number[]> = { 'first 10 s': [], '10-60 s': [], '1-10 min': [], '10-60 min': [] };
  const bandOf = (t: number) => (t < 11e6 ? 'first 10 s' : t < 61e6 ? '10-60 s' : t < 601e6 ? '1-10 min' : '10-60 min');
  let oneShotMax = 0;
  for (let t = scheduler.now(); t < HOUR_US; t += 1_000_000) {
    await scheduler.runUntil(t);
    const ahead = t + 10_000;
    for (const s of sessions) {
      const truth = sim.devices[s.info.name].clock.deviceTimeAt(ahead);
      const e = Math.abs(s.clock.clock.toDeviceExact(ahead) - truth);
      errors.push(e);
      bands[bandOf(t)].push(e);
      // One shot: device ≈ author + offset, with the device clock's wrap taken into account.
      const predicted = (ahead + oneShot[s.info.name]) % 4294967296;
      oneShotMax = Math.max(oneShotMax, Math.abs(u32Diff(Math.round(predicted) >>> 0, sim.devices[s.info.name].clock.microsAt(ahead))));
    }
  }
  errors.sort((a, b) => a - b);
  const wall = (performance.now() - started) / 1000;
  const result = {
    bench: 'sync',
    seed: SEED,
    p99ErrorUs: +errors[Math.floor(errors.length * 0.99)].toFixed(2),
    maxErrorUs: +errors[errors.length - 1].toFixed(2),
    medianErrorUs: +errors[errors.length >> 1].toFixed(2),
    oneShotMaxErrorUs: Math.round(oneShotMax),
    byTime: Object.fromEntries(
      Object.entries(bands)
        .filter(([, e]) => e.length > 0)
        .map(([band, e]) => {
          const s = [...e].sort((a, b) => a - b);
          return [band, { p50: +s[s.length >> 1].toFixed(1), p99: +s[Math.floor(s.length * 0.99)].toFixed(1), max: +s[s.length - 1].toFixed(1) }];
        }),
    ),
    targets: { p99ErrorUs: 10, maxErrorUs: 50 },
    simulatedSeconds: HOUR_US / 1e6,
    samples: errors.length,
    devices: preset.devices.map((d) => ({ name: d.name, ppm: +clocks[d.name].ppm.toFixed(1) })),
    link: PROFILE,
    oneWayDelay_us: Object.fromEntries(
      Object.entries(LINKS[PROFILE]).map(([dir, l]) => [dir, [l.baseDelay_us + l.jitterMin_us, l.baseDelay_us + 1000 + l.jitterMax_us]]),
    ),
    wallSeconds: +wall.toFixed(1),
  };
  await maxl.end();
  await sim.stop();
  return result;
}

const seeds = seedList();
const perSeed = [];
for (const seed of seeds) {
  const r = await runSeed(seed);
  perSeed.push(r);
  if (seeds.length > 1) console.error(`seed ${seed}: p99 ${r.p99ErrorUs} µs, max ${r.maxErrorUs} µs (${r.wallSeconds} s)`);
}
const worstP99 = perSeed.reduce((a, b) => (b.p99ErrorUs > a.p99ErrorUs ? b : a));
const worstMax = perSeed.reduce((a, b) => (b.maxErrorUs > a.maxErrorUs ? b : a));
const worst = { worstP99Us: worstP99.p99ErrorUs, worstP99Seed: worstP99.seed, worstMaxUs: worstMax.maxErrorUs, worstMaxSeed: worstMax.seed };
const result =
  seeds.length === 1
    ? { ...perSeed[0], ...worst }
    : {
        bench: 'sync',
        seeds,
        ...worst,
        targets: { p99ErrorUs: 10, maxErrorUs: 50 },
        // Per seed: p99 and max over its 3 devices × ~3600 s, and by time since begin().
        perSeed: perSeed.map((r) => ({ seed: r.seed, p99ErrorUs: r.p99ErrorUs, maxErrorUs: r.maxErrorUs, medianErrorUs: r.medianErrorUs, byTime: r.byTime })),
        link: PROFILE,
        wallSeconds: +perSeed.reduce((s, r) => s + r.wallSeconds, 0).toFixed(1),
      };
console.log(JSON.stringify(result));
