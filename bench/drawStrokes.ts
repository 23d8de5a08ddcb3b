/**
 * The draw bench's strokes (bench/draw.ts), in machine mm on the Blot's 125 mm bed,
 * and how its scripted pointer moves along them.
 */

/** ms between pointer moves (a 125 Hz mouse or pen). */
export const SAMPLE_MS = 8;
/** mm/s², the pointer's speeding up and slowing down at a stroke's ends. */
export const POINTER_ACCEL = 1000;


export type Path = (u: number) => [number, number];
export interface StrokeSpec {
  name: string;
  kind: 'smooth' | 'zigzag' | 'fast';
  speed: number;
  path: Path;
}

const circle = (cx: number, cy: number, r: number): Path => (u) => [cx + r * Math.cos(2 * Math.PI * u), cy + r * Math.sin(2 * Math.PI * u)];
const sine: Path = (u) => [15 + 90 * u, 64 + 6 * Math.sin((2 * Math.PI * 90 * u) / 45)];
const spiral: Path = (u) => {
  const a = 3 * Math.PI * u;
  const r = 8 + 12 * u;
  return [90 + r * Math.cos(a), 30 + r * Math.sin(a)];
};
const zigzagCorners: Array<[number, number]> = [[15, 95], [25, 85], [35, 95], [45, 85], [55, 95], [65, 85]];
const zigzag: Path = (u) => {
  const f = u * (zigzagCorners.length - 1);
  const i = Math.min(zigzagCorners.length - 2, Math.floor(f));
  const t = f - i;
  const [a, b] = [zigzagCorners[i], zigzagCorners[i + 1]];
  return [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
};

export const STROKES: StrokeSpec[] = [
  { name: 'circle r20', kind: 'smooth', speed: 50, path: circle(30, 30, 20) },
  { name: 'sine a6 λ45', kind: 'smooth', speed: 50, path: sine },
  { name: 'spiral r8–20', kind: 'smooth', speed: 50, path: spiral },
  { name: 'zigzag', kind: 'zigzag', speed: 50, path: zigzag },
  { name: 'fast circle r18', kind: 'fast', speed: 150, path: circle(100, 100, 18) },
];

/** The path by arc length: s (mm) → point, and the total length. */
export function byLength(path: Path): { length: number; at: (s: number) => [number, number] } {
  const n = 4000;
  const pts = Array.from({ length: n + 1 }, (_, i) => path(i / n));
  const cum = [0];
  for (let i = 1; i <= n; i++) cum.push(cum[i - 1] + Math.hypot(pts[i][0] - pts[i - 1][0], pts[i][1] - pts[i - 1][1]));
  const length = cum[n];
  return {
    length,
    at: (s) => {
      const target = Math.max(0, Math.min(length, s));
      let lo = 0;
      let hi = n;
      while (hi - lo > 1) {
        const mid = (lo + hi) >> 1;
        if (cum[mid] <= target) lo = mid;
        else hi = mid;
      }
      const f = cum[hi] > cum[lo] ? (target - cum[lo]) / (cum[hi] - cum[lo]) : 0;
      return [pts[lo][0] + f * (pts[hi][0] - pts[lo][0]), pts[lo][1] + f * (pts[hi][1] - pts[lo][1])];
    },
  };
}

/**
 * Distance along a stroke of `length` mm at time t (s): up to speed v at
 * POINTER_ACCEL, cruise, down to rest at the end. (The page's scripted pointer in
 * bench/draw.ts runs the same formula.)
 */
export function travelled(t: number, length: number, v: number): number {
  const ta = v / POINTER_ACCEL;
  const da = 0.5 * POINTER_ACCEL * ta * ta;
  const cruise = (length - 2 * da) / v;
  if (t <= ta) return 0.5 * POINTER_ACCEL * t * t;
  if (t <= ta + cruise) return da + v * (t - ta);
  if (t - ta - cruise >= ta) return length;
  return length - 0.5 * POINTER_ACCEL * (2 * ta + cruise - t) ** 2;
}
