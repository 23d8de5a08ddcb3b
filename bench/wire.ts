/**
 * npm run bench -- wire
 *
 * Bytes per second of motion on the wire, for the planner benchmark paths
 * (bench/paths.ts), streamed by the real runtime to the real firmware (wasm) of
 * the simulated Blot-like plotter: one board, CoreXY, two positional tracks
 * (a, b) and a pen event channel. The planner runs at the benchmark limits
 * (250 mm/s, 3000 mm/s², 0.05 mm junction deviation), the machine's soft limits
 * are lifted so the paths run as they are. Virtual time, deterministic.
 *
 * Bytes are counted at the simulated USB link, whole frames (COBS, CRC and the
 * delimiter included), both ways. The idle traffic (clock-sync PINGs and their
 * PONGs) is measured over the same span of time on the idle machine and given
 * apart, so `motionBytesPerS` is what the motion itself costs.
 *
 * WIRE_SEGMENTS (default 3000) sets how many segments of each path are streamed.
 */
import { blotPlotter } from '../core/sim/presets/index.ts';
import { runJob, startMachine } from '../core/system/harness.ts';
import { FrameReceiver } from '../core/net/frame.ts';
import { MessageType, nameOf } from '../core/net/protocol.ts';
import type { Link } from '../core/net/link.ts';
import { BENCH_LIMITS, benchPaths } from './paths.ts';

const SEGMENTS = Number(process.env.WIRE_SEGMENTS ?? 3000);
const BAUD_250000_BYTES_PER_S = 250_000 / 10; // the firmware's default baud, 8N1: ten bit times a byte

function preset() {
  const p = blotPlotter();
  p.config = { ...p.config, limits: BENCH_LIMITS, softLimits: undefined };
  return p;
}

/**
 * The link with its writes (author → device) also parsed into frames, counting
 * the bytes of each message type (frame and delimiter included).
 */
function tapWrites(link: Link, byType: Map<string, number>): Link {
  const receiver = new FrameReceiver(
    (p) => {
      const name = nameOf(MessageType, p.typeCode) ?? `0x${p.typeCode.toString(16)}`;
      byType.set(name, (byType.get(name) ?? 0) + pendingBytes);
      if (process.env.DEBUG) byType.set(`${name} frames`, (byType.get(`${name} frames`) ?? 0) + 1);
      pendingBytes = 0;
    },
    () => {},
  );
  let pendingBytes = 0;
  const writer = link.writable.getWriter();
  const writable = new WritableStream<Uint8Array>({
    write(chunk) {
      for (let i = 0; i < chunk.length; i++) {
        pendingBytes++;
        receiver.push(chunk.subarray(i, i + 1));
      }
      return writer.write(chunk);
    },
    close: () => writer.close(),
  });
  return { readable: link.readable, writable, label: link.label, close: () => link.close?.() ?? Promise.resolve() };
}

interface Counts {
  toDevice: number;
  toAuthor: number;
}

const results: Record<string, unknown> = {};
for (const path of benchPaths(SEGMENTS)) {
  const byType = new Map<string, number>();
  const b = await startMachine(preset(), { seed: 11, wrapLink: (l) => tapWrites(l, byType) });
  const counts = (): Counts => {
    const r = b.sim.linkReports().blot;
    return { toDevice: r.toDevice.bytesWritten, toAuthor: r.toAuthor.bytesWritten };
  };
  // Go to the path's start first, so the job is the path alone.
  await runJob(b, [{ endPosition: path.start }]);
  await b.scheduler.advance(500_000);

  let motion_s = 0;
  let segments = 0;
  b.maxl.queue.subscribe((e) => {
    if (e.type !== 'transmitted') return;
    for (const s of e.segments) {
      motion_s += s.duration_s;
      segments++;
    }
  });
  const before = counts();
  byType.clear();
  const t0 = b.scheduler.now();
  await runJob(
    b,
    path.points.map((p) => ({ endPosition: p })),
    undefined,
    5000,
    600_000_000,
  );
  const job = counts();
  const jobByType = Object.fromEntries([...byType].sort((x, y) => y[1] - x[1]).map(([k, v]) => [k, Math.round(v / motion_s)]));
  const span_us = b.scheduler.now() - t0;
  // The idle machine over the same span: what clock sync alone costs.
  await b.scheduler.advance(span_us);
  const idle = counts();
  const errors = b.events.filter((e) => e.type === 'error');
  if (errors.length) throw new Error(`${path.name}: ${errors.map((e) => e.text).join('; ')}`);

  const span_s = span_us / 1e6;
  const toDevice = job.toDevice - before.toDevice;
  const toAuthor = job.toAuthor - before.toAuthor;
  const idleToDevice = idle.toDevice - job.toDevice;
  const idleToAuthor = idle.toAuthor - job.toAuthor;
  const motionBytes = toDevice - idleToDevice;
  results[path.name] = {
    describe: path.describe,
    segments,
    motionS: +motion_s.toFixed(3),
    toDeviceBytesPerS: Math.round(toDevice / motion_s),
    toAuthorBytesPerS: Math.round(toAuthor / motion_s),
    idleToDeviceBytesPerS: Math.round(idleToDevice / span_s),
    idleToAuthorBytesPerS: Math.round(idleToAuthor / span_s),
    motionBytesPerS: Math.round(motionBytes / motion_s),
    motionBytesPerSegment: +(motionBytes / segments).toFixed(2),
    /** The share of the firmware's default 250 000 baud serial line the job needs toward the device. */
    shareOf250000Baud: +(toDevice / motion_s / BAUD_250000_BYTES_PER_S).toFixed(3),
    toDeviceBytesPerSByMessage: jobByType,
  };
  console.error(`[wire] ${path.name}: ${JSON.stringify(results[path.name])}`);
  await b.maxl.end();
  await b.sim.stop();
}

const worst = Math.max(...Object.values(results).map((r) => (r as { toDeviceBytesPerS: number }).toDeviceBytesPerS));
console.log(
  JSON.stringify({
    bench: 'wire',
    machine: 'blotPlotter (one board, CoreXY: tracks a, b; pen events), limits 250 mm/s, 3000 mm/s², 0.05 mm',
    segmentsPerPath: SEGMENTS,
    worstToDeviceBytesPerS: worst,
    paths: results,
  }),
);
