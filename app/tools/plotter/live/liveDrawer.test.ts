/**
 * Live drawing on the simulated Blot plotter (real firmware in wasm, the plant's
 * pen servo and ink), in virtual time: a pointer's points are fed as they would
 * arrive, one every 8 ms, while the machine runs.
 */
import { afterEach, describe, expect, it } from 'vitest';
import { startMachine, type Bench } from '../../../../core/system/harness.ts';
import { blotPlotter } from '../../../../core/sim/presets/blotPlotter.ts';
import { hausdorff, pointDrawingDistance } from '../geometry/hausdorff.ts';
import { penDefaults } from '../penDefaults.ts';
import { LiveDrawer, type LiveHost } from './liveDrawer.ts';
import { PlannedPen } from './plannedPen.ts';

/** ms between pointer points (a 125 Hz mouse). */
const SAMPLE_MS = 8;

interface Drawn {
  /** The pointer's points, x, y pairs, and the author µs of each. */
  xy: number[];
  t_us: number[];
}

let bench: Bench | null = null;
afterEach(async () => {
  await bench?.maxl.end();
  await bench?.sim.stop();
  bench = null;
});

async function setup(queueCapacity?: number) {
  const preset = blotPlotter();
  if (queueCapacity) preset.config.queueCapacity = queueCapacity;
  const b = await startMachine(preset, { sim: { toolTracePeriod_us: 1000 } });
  bench = b;
  const log: Array<{ level: string; code: string; message: string }> = [];
  let claimed = false;
  let releases = 0;
  const host: LiveHost = {
    maxl: b.maxl,
    claim: () => (claimed = true),
    release: () => {
      claimed = false;
      releases++;
    },
    log: (level, code, message) => log.push({ level, code, message }),
    strokeRefused: () => {},
  };
  const drawer = new LiveDrawer(host);
  drawer.attach(b.maxl);
  const pen = penDefaults({ motionAxes: ['x', 'y'], eventChannels: ['pen'], limits: { maxVelocity: 120 } }, 'blotPlotter')!;
  const planned = new PlannedPen(() => pen);
  planned.attach(b.maxl);
  return { b, drawer, pen, planned, log, claimed: () => claimed, releases: () => releases };
}

/** Feeds `path(s)` (s in mm along it, 0…length) as a pointer moving at `speed` mm/s would, one point per SAMPLE_MS. */
async function drawStroke(b: Bench, drawer: LiveDrawer, id: number, pen: ReturnType<typeof penDefaults>, length: number, speed: number, path: (s: number) => [number, number]): Promise<Drawn> {
  const drawn: Drawn = { xy: [], t_us: [] };
  const p0 = path(0);
  expect(drawer.start(id, p0, pen, 0.2)).toBe(true);
  drawn.xy.push(...p0);
  drawn.t_us.push(b.scheduler.now());
  const duration_ms = (length / speed) * 1000;
  for (let t = SAMPLE_MS; ; t += SAMPLE_MS) {
    await b.scheduler.advance(SAMPLE_MS * 1000);
    const p = path(Math.min(length, (t / 1000) * speed));
    drawer.points(id, p);
    drawn.xy.push(...p);
    drawn.t_us.push(b.scheduler.now());
    if (t >= duration_ms) break;
  }
  drawer.end(id);
  return drawn;
}

/** Runs until the drawer lets the machine go (everything drawn), syncing the plant. */
async function runUntilSettled(b: Bench, drawer: LiveDrawer, limit_us = 30_000_000): Promise<void> {
  const end = b.scheduler.now() + limit_us;
  while (drawer.active) {
    await b.scheduler.advance(5000);
    drawer.settle();
    if (b.scheduler.now() > end) throw new Error(`the strokes were not drawn in time: ${JSON.stringify(drawer.status())}; runtime: ${b.events.map((e) => e.text).join(' | ').slice(0, 800)}`);
  }
  await b.scheduler.advance(20_000);
  b.sim.sync();
}

/** An arc of radius r about (cx, cy) from angle a0, by arc length s. */
function arc(cx: number, cy: number, r: number, a0: number): (s: number) => [number, number] {
  return (s) => [cx + r * Math.cos(a0 + s / r), cy + r * Math.sin(a0 + s / r)];
}

function ink(b: Bench): number[][] {
  return (b.sim.plant.pen?.strokes ?? []).map((s) => s.x.flatMap((x, i) => [x, s.y[i]]));
}

describe('live drawing on the simulated Blot', () => {
  it('the machine follows a smooth stroke while it is drawn, never rests inside it, and its ink matches the stroke', { timeout: 60_000 }, async () => {
    const { b, drawer, pen, planned, log, releases } = await setup();
    const curve = arc(60, 60, 20, 0);
    const length = 2 * Math.PI * 20 * 0.9;
    const drawn = await drawStroke(b, drawer, 1, pen, length, 50, curve);
    const lastPoint_us = drawn.t_us.at(-1)!;
    await runUntilSettled(b, drawer);

    // The machine started drawing before the last point arrived.
    const trace = b.sim.plant.trace!;
    const strokes = b.sim.plant.pen!.strokes;
    expect(strokes).toHaveLength(1);
    const inkStart_us = strokes[0].t_us[0];
    expect(inkStart_us).toBeLessThan(lastPoint_us);
    // Half the stroke was inked before the pointer lifted.
    const inkedBeforeLift = strokes[0].t_us.filter((t) => t <= lastPoint_us).length;
    expect(inkedBeforeLift).toBeGreaterThan(strokes[0].t_us.length / 2);

    // Never at rest inside the stroke: from when the tool left the first point to when it reached the last, the planned speed stays up.
    const first = curve(0);
    const last = curve(length);
    let leftFirst = NaN;
    let reachedLast = NaN;
    for (let i = 0; i < trace.t_us.length; i++) {
      const x = trace.position.x[i];
      const y = trace.position.y[i];
      if (Number.isNaN(leftFirst) && trace.t_us[i] > inkStart_us && Math.hypot(x - first[0], y - first[1]) > 0.5) leftFirst = trace.t_us[i];
      if (!Number.isNaN(leftFirst) && Number.isNaN(reachedLast) && Math.hypot(x - last[0], y - last[1]) < 0.5) reachedLast = trace.t_us[i];
    }
    expect(reachedLast).toBeGreaterThan(leftFirst);
    let slowest = Infinity;
    for (let t = leftFirst; t < reachedLast; t += 1000) slowest = Math.min(slowest, b.maxl.sample(t).speed);
    expect(slowest).toBeGreaterThan(5);

    // The ink is the stroke (Hausdorff ≤ 0.3 mm), and nothing else.
    const error = hausdorff([drawn.xy], ink(b));
    expect(error).toBeLessThanOrEqual(0.3);
    expect(log.filter((l) => l.level !== 'info')).toEqual([]);
    // The plan's pen-down path is one stroke: the thinned points (within the 0.2 mm tolerance of the pointer's).
    expect(planned.strokes).toHaveLength(1);
    expect(hausdorff([drawn.xy], planned.strokes)).toBeLessThanOrEqual(0.2);
    // Everything drawn, the machine was given back.
    expect(drawer.active).toBe(false);
    expect(releases()).toBe(1);
  });

  it('a hand faster than the limits: the machine falls behind, every point waits in order, none is dropped', async () => {
    // A small queue (32 segments), so the hand runs ahead of what it holds.
    const { b, drawer, pen } = await setup(32);
    // 150 mm/s on a gentle zigzag of straight 30 mm legs, above the machine's 120 mm/s.
    const legs: Array<[number, number]> = [[10, 10], [40, 20], [70, 10], [100, 20], [70, 40], [40, 30], [10, 40], [40, 60], [70, 50], [100, 60], [110, 100], [20, 110]];
    const cumulative = [0];
    for (let i = 1; i < legs.length; i++) cumulative.push(cumulative[i - 1] + Math.hypot(legs[i][0] - legs[i - 1][0], legs[i][1] - legs[i - 1][1]));
    const length = cumulative.at(-1)!;
    const path = (s: number): [number, number] => {
      let i = 1;
      while (i < legs.length - 1 && cumulative[i] < s) i++;
      const f = (s - cumulative[i - 1]) / (cumulative[i] - cumulative[i - 1]);
      return [legs[i - 1][0] + f * (legs[i][0] - legs[i - 1][0]), legs[i - 1][1] + f * (legs[i][1] - legs[i - 1][1])];
    };
    let mostWaiting = 0;
    const drawn = await drawStroke(b, drawer, 1, pen, length, 150, (s) => {
      mostWaiting = Math.max(mostWaiting, drawer.status().waitingMoves);
      return path(s);
    });
    const behindAtLift = drawer.status().behind_mm;
    await runUntilSettled(b, drawer);
    expect(behindAtLift).toBeGreaterThan(10);
    expect(mostWaiting).toBeGreaterThan(20);
    // Every pointer point was drawn: each lies on the ink.
    const inked = ink(b);
    const missed = [];
    for (let i = 0; i < drawn.xy.length; i += 2) if (pointDrawingDistance(drawn.xy[i], drawn.xy[i + 1], inked) > 0.3) missed.push(i / 2);
    expect(missed).toEqual([]);
    expect(hausdorff([drawn.xy], inked)).toBeLessThanOrEqual(0.3);
  }, 60_000);

  it('a stroke leaving the soft limits: the part outside is refused with a note, the rest is drawn, no ink outside', async () => {
    const { b, drawer, pen, log } = await setup();
    // From (100, 50) right to x = 140 (the bed ends at 125), down, and back to (100, 60).
    const path = (s: number): [number, number] => {
      if (s <= 40) return [100 + s, 50];
      if (s <= 50) return [140, 50 + (s - 40)];
      return [140 - (s - 50), 60];
    };
    await drawStroke(b, drawer, 7, pen, 90, 40, path);
    await runUntilSettled(b, drawer);
    const note = log.find((l) => l.code === 'DRAW_OUTSIDE');
    expect(note?.message).toMatch(/Stroke 7 left the soft limits \(first point outside: 125\.\d, 50\.0 mm; the bed is 0–125 × 0–125 mm\): \d+\.\d mm outside were not drawn, the rest was/);
    // 15 + 10 + 15 mm outside, less what the pointer's samples cut off the corners.
    expect(Number(/: ([\d.]+) mm outside/.exec(note!.message)![1])).toBeCloseTo(40, 0);
    const inked = ink(b);
    expect(inked).toHaveLength(2);
    const inside = [[100, 50, 125, 50], [125, 60, 100, 60]];
    expect(hausdorff(inside, inked)).toBeLessThanOrEqual(0.3);
    for (const s of inked) for (let i = 0; i < s.length; i += 2) expect(s[i]).toBeLessThanOrEqual(125.3);
  }, 60_000);

  it('STOP drops the strokes not yet drawn, and says so', async () => {
    const { b, drawer, pen, log } = await setup();
    drawer.start(3, [10, 10], pen, 0.2);
    for (let i = 1; i <= 2000; i++) drawer.points(3, [10 + i * 0.05, 10 + (i % 2) * 20]);
    expect(drawer.status().waitingMoves).toBeGreaterThan(0);
    await b.scheduler.advance(300_000);
    drawer.stopped();
    expect(drawer.status().waitingMoves).toBe(0);
    expect(drawer.active).toBe(false);
    expect(log.find((l) => l.code === 'DRAW_DISCARDED')?.message).toMatch(/STOP: 1 stroke not drawn to the end \(3\) discarded, with \d+ moves that were waiting/);
    // Later points of that stroke are ignored.
    drawer.points(3, [50, 50]);
    expect(drawer.status().waitingMoves).toBe(0);
  });

  it('a stroke started while the machine is busy is refused with a note, and its points are ignored', async () => {
    const { b, pen } = await setup();
    const log: string[] = [];
    const refused: number[] = [];
    const drawer = new LiveDrawer({
      maxl: b.maxl,
      claim: () => {
        log.push('MACHINE_BUSY: Cannot draw a stroke: a job runs');
        return false;
      },
      release: () => {},
      log: (_level, code, message) => log.push(`${code}: ${message}`),
      strokeRefused: (id) => refused.push(id),
    });
    expect(drawer.start(4, [10, 10], pen, 0.2)).toBe(false);
    drawer.points(4, [20, 20, 30, 30]);
    drawer.end(4);
    expect(refused).toEqual([4]);
    expect(drawer.active).toBe(false);
    expect(b.maxl.queue.untransmittedCount).toBe(0);
    expect(drawer.status().lastId).toBe(4);
    // Without a pen channel: refused with the reason.
    const noPen = new LiveDrawer({ maxl: b.maxl, claim: () => true, release: () => {}, log: (_l, code, m) => log.push(`${code}: ${m}`), strokeRefused: () => {} });
    expect(noPen.start(5, [10, 10], null, 0.2)).toBe(false);
    expect(log.at(-1)).toMatch(/DRAW_REFUSED: Stroke not drawn: this machine has no event channel to drive a pen/);
  });
});
