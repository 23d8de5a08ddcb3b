/**
 * The cross-language fixture firmware/test/fixtures/segments.json: segments planned
 * and timed by the TypeScript core, encoded for one device, and the core's own
 * evaluation of every track at chosen device times. The C++ tests feed the frames
 * to the reader library and compare what its readers report.
 *
 *   npx tsx scripts/segment-fixture.ts          rewrites the file
 *   npx tsx scripts/segment-fixture.ts --check  fails if it is out of date
 */
import { readFileSync, writeFileSync, mkdirSync } from 'node:fs';
import { dirname } from 'node:path';
import { fileURLToPath } from 'node:url';
import { createMAXL, type MaxlConfig } from '../core/index.ts';
import { ClockMap, U32 } from '../core/net/clockMap.ts';
import { encodeFrame } from '../core/net/frame.ts';
import type { Message } from '../core/net/messages.ts';
import { PROTOCOL_VERSION, ReaderKind } from '../core/net/protocol.ts';
import { geometryMessages, timingMessages, type PositionSlot } from '../core/net/segmentEncoding.ts';
import { PHASE_STRIDE } from '../core/plan/phases.ts';
import { queueOf } from '../core/maxl.ts';

export const FIXTURE_PATH = fileURLToPath(new URL('../firmware/test/fixtures/segments.json', import.meta.url));

export interface FixtureReader {
  name: string;
  kind: number;
  slot: number;
}

export interface FixtureSample {
  t: number;
  positions: number[];
  velocity: number;
  /** null within 2 µs of a phase boundary, where acceleration jumps and µs rounding decides the side */
  acceleration: number | null;
}

export interface FixtureCase {
  name: string;
  describe: string;
  readers: FixtureReader[];
  frames: string[];
  receiveAt: number;
  samples: FixtureSample[];
}

interface CaseSpec {
  name: string;
  describe: string;
  config: MaxlConfig;
  start: number[];
  /** points to move to, and dwells (s) */
  path: Array<number[] | { dwell_s: number }>;
  /** position tracks this device reads, in slot order */
  tracks: string[];
  clock: { offset_us: number; ppm: number };
}

const LIMITS = { maxVelocity: 200, maxAcceleration: 2500, junctionDeviation: 0.05 };

const CASES: CaseSpec[] = [
  {
    name: 'square-x-stepper',
    describe: 'a square, read by an x position reader plus velocity and acceleration readers; device clock 120 ppm fast',
    config: { motionAxes: ['x', 'y'], limits: LIMITS },
    start: [0, 0],
    path: [[60, 0], [60, 40], [0, 40], [0, 0]],
    tracks: ['x'],
    clock: { offset_us: 7_000_000, ppm: 120 },
  },
  {
    name: 'corexy-plotter',
    describe: 'a zigzag with short pieces, CoreXY actuators a and b on one board; device clock 180 ppm slow',
    config: { motionAxes: ['x', 'y'], limits: LIMITS, transforms: [{ type: 'corexy', from: ['x', 'y'], to: ['a', 'b'] }] },
    start: [10, 10],
    path: [[12, 10], [12.5, 10.5], [14, 10.5], [14, 12], [30, 25], [31, 25], [31, 24], [10, 10]],
    tracks: ['a', 'b'],
    clock: { offset_us: 123_456_789, ppm: -180 },
  },
  {
    name: 'across-the-wrap',
    describe: 'a spiral-ish path timed so that the device clock wraps through 2^32 mid-segment',
    config: { motionAxes: ['x', 'y'], limits: LIMITS },
    start: [0, 0],
    path: Array.from({ length: 24 }, (_, k) => [20 * Math.cos(k / 3) * (1 + k / 24), 20 * Math.sin(k / 3) * (1 + k / 24)]),
    tracks: ['x', 'y'],
    clock: { offset_us: U32 - 1_300_000, ppm: 35 },
  },
  {
    name: 'plotter-with-dwells',
    describe: 'CoreXY strokes cut by dwells (a pen dropping and lifting: 120 ms and 90 ms) and an instant (a 0-s dwell)',
    config: { motionAxes: ['x', 'y'], limits: LIMITS, transforms: [{ type: 'corexy', from: ['x', 'y'], to: ['a', 'b'] }] },
    start: [5, 5],
    path: [[20, 5], { dwell_s: 0.12 }, [20, 15], [30, 15], { dwell_s: 0.09 }, [40, 30], { dwell_s: 0 }, [45, 30], { dwell_s: 0.12 }, [5, 5]],
    tracks: ['a', 'b'],
    clock: { offset_us: 42_000_000, ppm: 60 },
  },
];

function buildCase(spec: CaseSpec): FixtureCase {
  const maxl = createMAXL(spec.config, { initialPosition: spec.start });
  for (const p of spec.path) queueOf(maxl).append(Array.isArray(p) ? { endPosition: p } : p);
  queueOf(maxl).planToRest();
  const author0 = 1_000_000; // the job starts 1 s into the author's clock
  const segments = [];
  for (let s = queueOf(maxl).transmitNext(author0); s; s = queueOf(maxl).transmitNext(author0)) segments.push(s);
  const clock = new ClockMap(0, spec.clock.offset_us, 1 + spec.clock.ppm * 1e-6);

  const c = maxl.config;
  const slots: PositionSlot[] = spec.tracks.map((t) => {
    const m = c.motionAxes.indexOf(t);
    return m >= 0 ? { space: 'motion', index: m } : { space: 'actuator', index: c.actuatorAxes.indexOf(t) };
  });
  const readers: FixtureReader[] = [
    ...spec.tracks.map((name, slot) => ({ name, kind: ReaderKind.position, slot })),
    { name: 'speed', kind: ReaderKind.velocity, slot: 0 },
    { name: 'accel', kind: ReaderKind.acceleration, slot: 0 },
  ];
  const messages: Message[] = [
    { type: 'HELLO_REQUEST', protocol: PROTOCOL_VERSION },
    ...readers.map((r, i): Message => ({ type: 'SUBSCRIBE', reader: i, kind: r.kind, slot: r.slot })),
    ...geometryMessages(segments, slots, 1, true),
    ...timingMessages(segments, clock, 1, true, LIMITS.maxAcceleration),
  ];
  const frames = messages.map((m, seq) => Buffer.from(encodeFrame(seq, m)).toString('hex'));

  // Sample every 3.7 ms from 1 ms before the first segment to 1 ms after the last.
  const first = segments[0].startTime_us;
  const last = segments[segments.length - 1].endTime_us;
  const boundaries = segments.flatMap((s) => {
    const out = [];
    for (let o = 0; o < s.timing!.length; o += PHASE_STRIDE) out.push(s.startTime_us + s.timing![o] * 1e6);
    out.push(s.endTime_us);
    return out;
  });
  const samples: FixtureSample[] = [];
  for (let ta = first - 1000; ta <= last + 1000; ta += 3700) {
    const t = clock.toDevice(ta);
    const author = clock.toAuthor(t, ta); // the author time of that whole device µs
    const at = maxl.sample(author);
    const positions = slots.map((s) => (s.space === 'motion' ? at.position[s.index] : at.actuator[s.index]));
    const nearBoundary = boundaries.some((b) => Math.abs(b - author) < 2);
    samples.push({
      t,
      positions,
      velocity: at.speed / clock.rate,
      acceleration: nearBoundary ? null : at.pathAcceleration / (clock.rate * clock.rate),
    });
  }
  return { name: spec.name, describe: spec.describe, readers, frames, receiveAt: clock.toDevice(first - 20_000), samples };
}

export function buildFixture(): { positionUnit: string; cases: FixtureCase[] } {
  return { positionUnit: 'mm', cases: CASES.map(buildCase) };
}

export function fixtureJson(): string {
  return `${JSON.stringify(buildFixture(), null, 1)}\n`;
}

if (process.argv[1] && fileURLToPath(import.meta.url) === process.argv[1]) {
  const text = fixtureJson();
  if (process.argv.includes('--check')) {
    if (readFileSync(FIXTURE_PATH, 'utf8') !== text) {
      console.error(`${FIXTURE_PATH} is out of date: run npx tsx scripts/segment-fixture.ts`);
      process.exit(1);
    }
    console.log('segment fixture up to date');
  } else {
    mkdirSync(dirname(FIXTURE_PATH), { recursive: true });
    writeFileSync(FIXTURE_PATH, text);
    console.log(`wrote ${buildFixture().cases.length} cases to ${FIXTURE_PATH}`);
  }
}
