/**
 * The benchmark paths shared by the planner and wire benchmarks, 100 000 segments
 * each unless asked otherwise. Deterministic: the random walk is seeded.
 */
import { seededRandom } from '../core/random.ts';

export interface BenchPath {
  name: string;
  describe: string;
  start: number[];
  points: number[][];
}

/** Archimedean spiral r = r0 + pitch·θ/2π with a point every `step` mm of arc. */
export function fineSpiral(count = 100_000, step = 0.2, r0 = 10, pitch = 1.5): BenchPath {
  const points: number[][] = [];
  let theta = 0;
  for (let k = 0; k < count; k++) {
    const r = r0 + (pitch * theta) / (2 * Math.PI);
    // ds ≈ √(r² + (dr/dθ)²)·dθ, so dθ = step / √(r² + (pitch/2π)²).
    theta += step / Math.hypot(r, pitch / (2 * Math.PI));
    const r1 = r0 + (pitch * theta) / (2 * Math.PI);
    points.push([r1 * Math.cos(theta), r1 * Math.sin(theta)]);
  }
  return { name: 'spiral', describe: `fine spiral, a point every ${step} mm`, start: [r0, 0], points };
}

/** Raster zigzag: rows of 1 mm pieces, 0.1 mm apart. */
export function rasterZigzag(count = 100_000, piece = 1, rowPitch = 0.1, width = 50): BenchPath {
  const points: number[][] = [];
  const perRow = Math.round(width / piece);
  let row = 0;
  while (points.length < count) {
    const y = row * rowPitch;
    const forward = row % 2 === 0;
    for (let i = 1; i <= perRow && points.length < count; i++) points.push([forward ? i * piece : width - i * piece, y]);
    if (points.length < count) points.push([forward ? width : 0, y + rowPitch]);
    row++;
  }
  return { name: 'raster', describe: `raster zigzag, ${piece} mm pieces, ${rowPitch} mm rows`, start: [0, 0], points };
}

/** Seeded random walk: steps of 0.05–5 mm in a direction that wanders by up to ±90° per step. */
export function randomWalk(count = 100_000, seed = 42): BenchPath {
  const rand = seededRandom(seed);
  const points: number[][] = [];
  let x = 0;
  let y = 0;
  let heading = 0;
  for (let k = 0; k < count; k++) {
    const length = 0.05 + rand() * 4.95;
    heading += (rand() - 0.5) * Math.PI;
    x += length * Math.cos(heading);
    y += length * Math.sin(heading);
    points.push([x, y]);
  }
  return { name: 'randomWalk', describe: 'seeded random walk, 0.05–5 mm steps', start: [0, 0], points };
}

/**
 * One turn of a circle flattened into `count` chords of `step` mm: a finely
 * flattened curve, as SVG and G-code import make. 100 000 chords of 3 µm give
 * r = count·step/2π ≈ 47.7 mm. The chord k spans the angle 2π/count, and its
 * length is 2r·sin(π/count), which is `step` to within 1e-10 relative.
 */
export function fineCircle(count = 100_000, step = 0.003): BenchPath {
  const r = (count * step) / (2 * Math.PI);
  const points: number[][] = [];
  for (let k = 1; k <= count; k++) {
    const theta = (2 * Math.PI * k) / count;
    points.push([r * Math.cos(theta), r * Math.sin(theta)]);
  }
  return { name: 'fineCircle', describe: `one turn of a circle, r ${r.toFixed(2)} mm, in ${count} chords of ${step * 1000} µm`, start: [r, 0], points };
}

export function benchPaths(count = 100_000): BenchPath[] {
  return [fineSpiral(count), rasterZigzag(count), randomWalk(count)];
}

export const BENCH_LIMITS = { maxVelocity: 250, maxAcceleration: 3000, junctionDeviation: 0.05 };
