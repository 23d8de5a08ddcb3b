/**
 * The author's segment encoding, checked by a reference reading of the wire
 * (docs/protocol.md §5) written here from the spec: decode the fixture's frames,
 * rebuild σ(t) from durations and alpha, and compare every slot's position with
 * the core's own evaluation. The C++ reader library runs the same fixture.
 */
import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import { decodeFrame } from './frame.ts';
import type { MessageOf } from './messages.ts';
import { shapePhaseCount } from './messages.ts';
import { ClockMap, u32Diff } from './clockMap.ts';
import { POSITION_SCALE } from './protocol.ts';
import { buildFixture, FIXTURE_PATH, fixtureJson, type FixtureCase } from '../../scripts/segment-fixture.ts';

interface WireSegment {
  p0: number[];
  p1: number[];
  length: number;
  start: number;
  durations: number[];
  signs: number[];
  alpha: number;
}

/** Rebuilds the device's segments from the frames, as a reader would. */
function readWire(c: FixtureCase): WireSegment[] {
  const slots = c.readers.filter((r) => r.kind === 1).length;
  const segs: WireSegment[] = [];
  let prevEnd: number[] = [];
  let timed = 0;
  let clock = 0;
  for (const hex of c.frames) {
    const { message } = decodeFrame(Buffer.from(hex, 'hex'), { positionSlots: slots, channels: 0 });
    if (message.type === 'GEOMETRY') {
      const g = message as MessageOf<'GEOMETRY'>;
      if (g.p0) prevEnd = g.p0;
      for (const s of g.segments) {
        segs.push({ p0: prevEnd, p1: s.p1, length: s.length, start: 0, durations: [], signs: [], alpha: 0 });
        prevEnd = s.p1;
      }
    } else if (message.type === 'TIMING') {
      const t = message as MessageOf<'TIMING'>;
      if (t.start !== undefined) clock = t.start;
      for (const s of t.segments) {
        const seg = segs[timed++];
        seg.start = clock;
        seg.durations = s.durations;
        seg.signs = Array.from({ length: shapePhaseCount(s.shape) }, (_, k) => [0, 1, 0, -1][(s.shape >> (2 * k)) & 3]);
        seg.alpha = s.alpha;
        clock = (clock + s.durations.reduce((a, b) => a + b, 0)) >>> 0;
      }
    }
  }
  return segs;
}

/** σ, σ′ (1/s) and σ″ (1/s²) at `local` µs into a segment, per §5: ν₀ = (1 − α·Q)/T. */
function sigmaAt(seg: WireSegment, local: number): [number, number, number] {
  const d = seg.durations.map((x) => x * 1e-6);
  const T = d.reduce((a, b) => a + b, 0);
  let Q = 0;
  for (let k = 0; k < d.length; k++) Q += seg.signs[k] * (d[k] * d[k] / 2 + d[k] * d.slice(k + 1).reduce((a, b) => a + b, 0));
  let nu = (1 - seg.alpha * Q) / T;
  let sigma = 0;
  let tau = Math.min(Math.max(local * 1e-6, 0), T);
  for (let k = 0; k < d.length; k++) {
    const a = seg.signs[k] * seg.alpha;
    const dt = Math.min(tau, d[k]);
    if (tau <= d[k] || k === d.length - 1) return [sigma + nu * dt + (a * dt * dt) / 2, nu + a * dt, a];
    sigma += nu * d[k] + (a * d[k] * d[k]) / 2;
    nu += a * d[k];
    tau -= d[k];
  }
  return [1, nu, 0];
}

describe('segment encoding (the cross-language fixture)', () => {
  it('is what scripts/segment-fixture.ts generates', () => {
    expect(readFileSync(FIXTURE_PATH, 'utf8')).toBe(fixtureJson());
  });

  for (const c of buildFixture().cases) {
    it(`reproduces the core's tracks from the wire alone: ${c.name}`, () => {
      const segs = readWire(c);
      expect(segs.length).toBeGreaterThan(3);
      let checked = 0;
      for (const sample of c.samples) {
        // The segment running at t: the last to start at or before it (wrap-safe).
        let i = -1;
        for (let k = 0; k < segs.length; k++) if (u32Diff(sample.t, segs[k].start) >= 0) i = k;
        let positions: number[];
        let v = 0;
        let a = 0;
        if (i < 0) positions = segs[0].p0.map((p) => p / POSITION_SCALE);
        else {
          const seg = segs[i];
          const [sigma, rate, accel] = sigmaAt(seg, u32Diff(sample.t, seg.start));
          positions = seg.p0.map((p, k) => (p + (seg.p1[k] - p) * sigma) / POSITION_SCALE);
          const done = u32Diff(sample.t, seg.start) >= seg.durations.reduce((x, y) => x + y, 0);
          v = done ? 0 : seg.length * rate;
          a = done ? 0 : seg.length * accel;
        }
        // µs rounding of boundaries moves a position by at most v·0.5 µs; Q16 by 8 nm.
        sample.positions.forEach((p, k) => expect(Math.abs(positions[k] - p)).toBeLessThan(2e-4));
        expect(Math.abs(v - sample.velocity)).toBeLessThan(0.02);
        if (sample.acceleration !== null) expect(Math.abs(a - sample.acceleration)).toBeLessThan(1);
        checked++;
      }
      expect(checked).toBe(c.samples.length);
    });
  }

  it('crosses the 32-bit wrap inside the motion in the wrap case', () => {
    const c = buildFixture().cases.find((x) => x.name === 'across-the-wrap')!;
    const ts = c.samples.map((s) => s.t);
    const moving = c.samples.filter((s) => s.velocity > 1).map((s) => s.t);
    expect(moving.some((t) => t > 2 ** 32 - 1e6)).toBe(true); // moving just before the wrap…
    expect(moving.some((t) => t < 1e6)).toBe(true); // …and just after it
    expect(ts.length).toBeGreaterThan(100);
  });

  it('maps device readings back to author time across the wrap', () => {
    const clock = new ClockMap(1e6, 2 ** 32 - 500, 1.0002);
    for (const author of [1e6, 1e6 + 400, 1e6 + 600, 1e6 + 5e6]) {
      const dev = clock.toDevice(author);
      expect(Math.abs(clock.toAuthor(dev, author + 1000) - author)).toBeLessThan(1);
    }
  });
});
