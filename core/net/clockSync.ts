/**
 * Clock synchronisation for one device (docs/design.md, decision 3): fit the device's
 * free-running µs counter as a line in author time, D(a) = D₀ + r·(a − a₀), from
 * ping exchanges, and keep refitting it during the job.
 *
 * ## What one exchange says
 * The author sends at a₁ (its clock), the device reads the ping at d₁ and replies
 * at d₂ (its clock), the author reads the pong at a₂. With one-way delays
 * δ↑, δ↓ ≥ their floors f↑, f↓:
 *   d₁ = D(a₁ + δ↑) ≥ D(a₁) + r·f↑      the up point lies above the line
 *   d₂ = D(a₂ − δ↓) ≤ D(a₂) − r·f↓      the down point lies below it
 * So the true line runs between the lower envelope of the up points and the upper
 * envelope of the down points. If the floors are equal (a symmetric link at its
 * fastest; a constant asymmetry is invisible to any two-way protocol), the line
 * is exactly midway between the two envelopes.
 *
 * ## Why envelopes, not the fastest round trips
 * Keeping only exchanges with a small RTT needs *both* directions fast at once,
 * which is rare; taking each direction's fastest separately needs each to be fast
 * on its own. And where the link adds a second independent wait (USB polls once
 * per 1 ms frame), the fastest of n exchanges approaches the floor only like 1/√n,
 * so the envelopes use every exchange of the window at once rather than slices.
 *
 * ## The fit, in two parts
 * For a rate r, measure everything against a line of that slope through (a₀, 0):
 *   u = d₁ − r·(a₁ − a₀)   (up)        w = d₂ − r·(a₂ − a₀)   (down)
 * 1. The rate. Cut the window into slices (at least 40 exchanges or 1/12 of the
 *    window each); in each, the up points' lowest u and the down points' highest w
 *    bracket the line, and their midpoint m_b is one estimate of it at time t_b. A
 *    least-squares line through the (t_b, m_b) corrects r; two passes settle it. A
 *    constant bias of the midpoints (uneven floors) does not tilt that line, and
 *    the scatter of many slices averages out.
 * 2. The offset. The envelopes of every exchange in the window, at that rate:
 *    D(a₀) = (min u + max w)/2. The more exchanges, the nearer each envelope comes
 *    to its floor (on a link that also waits for 1 ms USB frames, only like 1/√n).
 * Until the window spans half a second the rate is held (1 at first) and only the
 * offset is fitted.
 *
 * A one-shot offset set at start-up (the paper's method) drifts by up to 0.72 s
 * an hour with ±200 ppm crystals; this model follows the drift.
 */
import { ClockMap, u32Diff } from './clockMap.ts';

export interface PingStamps {
  /** author µs when the ping was written */
  authorSend: number;
  /** author µs when the pong was read */
  authorReceive: number;
  /** device µs (u32) when the ping arrived */
  deviceReceive: number;
  /** device µs (u32) when the pong was written */
  deviceReply: number;
}

export interface ClockSyncOptions {
  /** fit over this much recent author time (µs) */
  window_us: number;
  /** hold the rate until the window spans this much (µs) */
  minSpanForRate_us: number;
  /** refit at most this often (µs) once the model exists */
  refitEvery_us: number;
}

export const DEFAULT_CLOCK_SYNC: ClockSyncOptions = {
  window_us: 1_200_000_000,
  minSpanForRate_us: 500_000,
  refitEvery_us: 1_000_000,
};

export class ClockSync {
  private readonly options: ClockSyncOptions;
  // The exchanges held, as parallel arrays (device times unwrapped).
  private a1: number[] = [];
  private a2: number[] = [];
  private d1: number[] = [];
  private d2: number[] = [];
  private lastDeviceU32 = 0;
  private lastDeviceUnwrapped: number | null = null;
  private model: ClockMap | null = null;
  private lastFit = -Infinity;
  private rttRecent: number[] = [];
  private spread = Infinity;
  /** Exchanges folded in so far. */
  samples = 0;

  constructor(options: Partial<ClockSyncOptions> = {}) {
    this.options = { ...DEFAULT_CLOCK_SYNC, ...options };
  }

  /** The current model, or null before the first exchange. */
  get clock(): ClockMap | null {
    return this.model;
  }

  /** Adds one ping exchange (refitting when due) and returns its round-trip time in µs. */
  add(stamps: PingStamps): number {
    const held = u32Diff(stamps.deviceReply, stamps.deviceReceive);
    const d1 = this.unwrap(stamps.deviceReceive);
    const rate = this.model?.rate ?? 1;
    const rtt = stamps.authorReceive - stamps.authorSend - held / rate;
    this.a1.push(stamps.authorSend);
    this.a2.push(stamps.authorReceive);
    this.d1.push(d1);
    this.d2.push(d1 + held);
    this.samples++;
    this.rttRecent.push(rtt);
    if (this.rttRecent.length > 64) this.rttRecent.shift();

    const oldest = stamps.authorReceive - this.options.window_us;
    let drop = 0;
    while (drop < this.a1.length - 2 && this.a1[drop] < oldest) drop++;
    if (drop > 256 || (drop > 0 && drop * 2 > this.a1.length)) {
      this.a1 = this.a1.slice(drop);
      this.a2 = this.a2.slice(drop);
      this.d1 = this.d1.slice(drop);
      this.d2 = this.d2.slice(drop);
    }
    const now = stamps.authorReceive;
    // Refit often while the window is young (the model is still converging), then
    // less often: a settled model extrapolates well, and a refit costs O(window).
    const age = now - this.a1[0];
    const every = age < 10 * this.options.refitEvery_us ? this.options.refitEvery_us / 10 : age < 60 * this.options.refitEvery_us ? this.options.refitEvery_us : 10 * this.options.refitEvery_us;
    if (this.model === null || this.samples < 32 || now - this.lastFit >= every) {
      this.fit(oldest);
      this.lastFit = now;
    }
    return rtt;
  }

  /** Round-trip time: the median of the recent exchanges (µs). */
  get rtt(): number {
    if (this.rttRecent.length === 0) return NaN;
    const s = [...this.rttRecent].sort((x, y) => x - y);
    return s[s.length >> 1];
  }

  /** A high round-trip time: the largest recent one (µs), for safe lead times. */
  get rttHigh(): number {
    return this.rttRecent.length === 0 ? NaN : Math.max(...this.rttRecent);
  }

  /**
   * An estimate of the model's error (µs): how far the offset would move if only
   * the last quarter of the window's exchanges were used. Infinity before a model.
   * It cannot see a constant asymmetry of the link (nothing can).
   */
  get errorEstimate_us(): number {
    return this.model === null ? Infinity : this.spread;
  }

  private unwrap(u32: number): number {
    this.lastDeviceUnwrapped = this.lastDeviceUnwrapped === null ? u32 : this.lastDeviceUnwrapped + u32Diff(u32, this.lastDeviceU32);
    this.lastDeviceU32 = u32;
    return this.lastDeviceUnwrapped;
  }

  private fit(oldest: number): void {
    let first = 0;
    while (first < this.a1.length - 1 && this.a1[first] < oldest) first++;
    const n = this.a1.length - first;
    const a0 = this.a2[this.a2.length - 1]; // reference: the newest exchange
    const span = a0 - this.a1[first];
    let rate = this.model?.rate ?? 1;
    const up = lowerHull(this.a1, this.d1, first, a0);
    const down = upperHull(this.a2, this.d2, first, a0);
    if (span >= this.options.minSpanForRate_us && n >= 24) {
      // Least squares over slice midpoints: a robust rate.
      const perSlice = Math.max(40, Math.ceil(n / 12));
      for (let pass = 0; pass < 2; pass++) {
        const t: number[] = [];
        const m: number[] = [];
        for (let i = first; i < this.a1.length; i += perSlice) {
          const end = Math.min(this.a1.length, i + perSlice);
          if (end - i < perSlice / 2) break;
          let U = Infinity;
          let W = -Infinity;
          let tU = 0;
          let tW = 0;
          for (let k = i; k < end; k++) {
            const u = this.d1[k] - rate * (this.a1[k] - a0);
            const w = this.d2[k] - rate * (this.a2[k] - a0);
            if (u < U) ((U = u), (tU = this.a1[k]));
            if (w > W) ((W = w), (tW = this.a2[k]));
          }
          t.push((tU + tW) / 2 - a0);
          m.push((U + W) / 2);
        }
        if (t.length < 3) break;
        let mt = 0;
        let mm = 0;
        for (let k = 0; k < t.length; k++) ((mt += t[k]), (mm += m[k]));
        mt /= t.length;
        mm /= t.length;
        let stt = 0;
        let stm = 0;
        for (let k = 0; k < t.length; k++) ((stt += (t[k] - mt) ** 2), (stm += (t[k] - mt) * (m[k] - mm)));
        if (stt <= 0) break;
        rate += stm / stt;
      }
    }
    const offset = (envelope(up, rate, Math.min) + envelope(down, rate, Math.max)) / 2;
    this.model = new ClockMap(a0, offset, rate);
    // Error estimate: how far the last quarter's envelopes alone would put the offset.
    const recent = this.firstSentAfter(a0 - span / 4);
    if (recent < this.a1.length - 8) {
      const alone = (envelope(lowerHull(this.a1, this.d1, recent, a0), rate, Math.min) + envelope(upperHull(this.a2, this.d2, recent, a0), rate, Math.max)) / 2;
      this.spread = Math.abs(alone - offset);
    }
  }

  /** Index of the first exchange sent at or after author time t. */
  private firstSentAfter(t: number): number {
    let lo = 0;
    let hi = this.a1.length;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (this.a1[mid] < t) lo = mid + 1;
      else hi = mid;
    }
    return lo;
  }
}

/** Points (t − a₀, y) of a convex hull, in time order. */
type Hull = Array<[number, number]>;

/** min or max over hull vertices of y − r·t. */
function envelope(hull: Hull, r: number, pick: (a: number, b: number) => number): number {
  let best = hull[0][1] - r * hull[0][0];
  for (let k = 1; k < hull.length; k++) best = pick(best, hull[k][1] - r * hull[k][0]);
  return best;
}

/** cross product of (b − a) × (c − a): > 0 for a left turn. */
function cross(a: [number, number], b: [number, number], c: [number, number]): number {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/** Lower convex hull (Andrew's monotone chain) of points sorted by t. */
function lowerHull(ts: number[], ys: number[], from: number, t0: number): Hull {
  const h: Hull = [];
  for (let i = from; i < ts.length; i++) {
    const p: [number, number] = [ts[i] - t0, ys[i] - ys[ys.length - 1]];
    while (h.length >= 2 && cross(h[h.length - 2], h[h.length - 1], p) <= 0) h.pop();
    h.push(p);
  }
  for (const p of h) p[1] += ys[ys.length - 1];
  return h;
}

/** Upper convex hull of points sorted by t. */
function upperHull(ts: number[], ys: number[], from: number, t0: number): Hull {
  const h: Hull = [];
  for (let i = from; i < ts.length; i++) {
    const p: [number, number] = [ts[i] - t0, ys[i] - ys[ys.length - 1]];
    while (h.length >= 2 && cross(h[h.length - 2], h[h.length - 1], p) >= 0) h.pop();
    h.push(p);
  }
  for (const p of h) p[1] += ys[ys.length - 1];
  return h;
}
