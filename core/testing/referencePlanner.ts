/**
 * A deliberately simple batch planner, for tests only: written from the
 * definitions, sharing no code with core/plan, and O(n²).
 *
 * With e_k the squared speed at junction k, the constraints are upper bounds
 * e_k ≤ cap_k and differences e_k ≤ e_{k±1} + 2·a·L (speeding up or slowing down
 * across one block). The largest solution of such a system is, at each junction,
 * the smallest bound reachable from any junction i:
 *   e_k = min over i of ( cap_i + 2·Σ_{blocks between i and k} a·L ).
 * Start and end are at rest (cap = 0).
 */
export interface RefLimits {
  maxSpeed: number;
  maxAccel: number;
  axisMaxSpeed: number[];
  axisMaxAccel: number[];
  junctionDeviation: number;
}

export interface RefBlock {
  length: number;
  unit: number[];
  cruise: number;
  accel: number;
}

function along(magnitude: number, perAxis: number[], u: number[]): number {
  // Largest L with |L·u| ≤ magnitude and |L·u_i| ≤ perAxis_i.
  let best = magnitude;
  u.forEach((c, i) => {
    if (Math.abs(c) > 1e-15) best = Math.min(best, perAxis[i] / Math.abs(c));
  });
  return best;
}

export function refBlocks(points: number[][], limits: RefLimits, maxVelocities: number[]): RefBlock[] {
  const blocks: RefBlock[] = [];
  // A move shorter than 1e-9 mm from the last kept point is skipped (it adds no block).
  let from = points[0];
  for (let k = 1; k < points.length; k++) {
    const d = points[k].map((v, i) => v - from[i]);
    const length = Math.hypot(...d);
    if (length < 1e-9) continue;
    from = points[k];
    const unit = d.map((v) => v / length);
    blocks.push({
      length,
      unit,
      cruise: Math.min(maxVelocities[k - 1] ?? Infinity, along(limits.maxSpeed, limits.axisMaxSpeed, unit)),
      accel: along(limits.maxAccel, limits.axisMaxAccel, unit),
    });
  }
  return blocks;
}

/**
 * Junction cap from the geometry of the corner: the half-angle by atan2 (robust at
 * both ends, where acos is not), then the textbook v² = a·δ·sin(θ/2)/(1 − sin(θ/2)).
 */
export function refJunctionCap2(a: RefBlock, b: RefBlock, limits: RefLimits): number {
  const sum = Math.hypot(...a.unit.map((v, i) => v + b.unit[i]));
  const diff = Math.hypot(...a.unit.map((v, i) => b.unit[i] - v));
  const half = Math.atan2(sum, diff); // θ/2, θ between −u_in and u_out
  const s = Math.sin(half);
  let junction = Infinity;
  if (diff > 0) {
    const accel = along(limits.maxAccel, limits.axisMaxAccel, b.unit.map((v, i) => (v - a.unit[i]) / diff));
    junction = 1 - s <= 0 ? Infinity : (accel * limits.junctionDeviation * s) / (1 - s);
  }
  return Math.min(junction, a.cruise ** 2, b.cruise ** 2);
}

/** Optimal squared junction speeds e_0 … e_n (e_0 = e_n = 0). */
export function refJunctionSpeeds2(blocks: RefBlock[], limits: RefLimits): number[] {
  const n = blocks.length;
  const caps = [0];
  for (let k = 1; k < n; k++) caps.push(refJunctionCap2(blocks[k - 1], blocks[k], limits));
  caps.push(0);
  const e: number[] = [];
  for (let k = 0; k <= n; k++) {
    let best = Infinity;
    for (let i = 0; i <= n; i++) {
      let w = 0;
      for (let m = Math.min(i, k); m < Math.max(i, k); m++) w += blocks[m].accel * blocks[m].length;
      best = Math.min(best, caps[i] + 2 * w);
    }
    e.push(best);
  }
  return e;
}

/** Time to cross a block from entry² to exit², as fast as cruise and accel allow. */
export function refBlockTime(b: RefBlock, entry2: number, exit2: number): number {
  const a = b.accel;
  const peak2 = Math.min(b.cruise ** 2, (2 * a * b.length + entry2 + exit2) / 2);
  const peak = Math.sqrt(Math.max(peak2, entry2, exit2));
  const ve = Math.sqrt(entry2);
  const vx = Math.sqrt(exit2);
  const rampDistance = (2 * peak * peak - entry2 - exit2) / (2 * a);
  return (peak - ve) / a + (peak - vx) / a + Math.max(0, b.length - rampDistance) / peak;
}

export function refDuration(points: number[][], limits: RefLimits, maxVelocities: number[] = []): number {
  const blocks = refBlocks(points, limits, maxVelocities);
  const e = refJunctionSpeeds2(blocks, limits);
  return blocks.reduce((t, b, k) => t + refBlockTime(b, e[k], e[k + 1]), 0);
}
