/**
 * Clock synchronisation for one device (DESIGN.md decision 3): fit the device's
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
 * ## The fit
 * For a rate r, measure everything against a line of that slope through (a₀, 0):
 *   U(r) = minᵢ ( d₁ᵢ − r·(a₁ᵢ − a₀) )       the up points' lower envelope
 *   W(r) = maxᵢ ( d₂ᵢ − r·(a₂ᵢ − a₀) )       the down points' upper envelope
 * For the true rate both envelopes are flat in time and the gap G(r) = U(r) − W(r)
 * is as wide as it gets; a wrong slope tilts the points, so an envelope point at
 * one end of the window closes the gap (Moon, Skelly and Towsley 1999 bound skew
 * with the same hulls). U is a minimum of linear functions of r (concave) and W
 * a maximum (convex), so G is concave: a ternary search finds its maximum, over
 * the vertices of the two convex hulls only (the lower hull of the up points, the
 * upper hull of the down points), which are few. The line is then
 *   D(a) = (U + W)/2 + r·(a − a₀).
 * Until the window spans a few seconds the rate is held (1 at first) and only the
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
  /** search the rate within ± this of the last estimate (parts per million) */
  rateSearch_ppm: number;
  /** refit at most this often (µs) once the model exists */
  refitEvery_us: number;
}

export const DEFAULT_CLOCK_SYNC: ClockSyncOptions = {
  window_us: 600_000_000,
  minSpanForRate_us: 2_000_000,
  rateSearch_ppm: 1000,
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
    if (this.model === null || this.samples < 32 || now - this.lastFit >= this.options.refitEvery_us) {
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
   * the most recent quarter of the window were used. Infinity before a model.
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
    const a0 = this.a2[this.a2.length - 1]; // reference: the newest exchange
    const up = lowerHull(this.a1, this.d1, first, a0);
    const down = upperHull(this.a2, this.d2, first, a0);
    const gapAt = (r: number) => envelope(up, r, Math.min) - envelope(down, r, Math.max);
    let rate = this.model?.rate ?? 1;
    const span = this.a2[this.a2.length - 1] - this.a1[first];
    if (span >= this.options.minSpanForRate_us) {
      let lo = rate - this.options.rateSearch_ppm * 1e-6;
      let hi = rate + this.options.rateSearch_ppm * 1e-6;
      for (let k = 0; k < 80; k++) {
        const m1 = lo + (hi - lo) / 3;
        const m2 = hi - (hi - lo) / 3;
        if (gapAt(m1) < gapAt(m2)) lo = m1;
        else hi = m2;
      }
      rate = (lo + hi) / 2;
    }
    const offset = (envelope(up, rate, Math.min) + envelope(down, rate, Math.max)) / 2;
    this.model = new ClockMap(a0, offset, rate);
    // Error estimate: how far the recent quarter's envelopes alone would move the offset.
    const recent = Math.max(first, this.a1.length - Math.max(8, (this.a1.length - first) >> 2));
    const U4 = envelope(lowerHull(this.a1, this.d1, recent, a0), rate, Math.min);
    const W4 = envelope(upperHull(this.a2, this.d2, recent, a0), rate, Math.max);
    this.spread = Math.abs((U4 + W4) / 2 - offset);
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
