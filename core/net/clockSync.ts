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
 * If r is the true rate, u = D(a₀) + r·δ↑ (each up point sits above the line by its
 * delay) and w = D(a₀) − r·δ↓; if r is off by ε, both also tilt by ε·(a − a₀).
 * 1. The rate: least squares through each direction's fast edge (fitRate below).
 *    Cut the window into slices of 64 exchanges (more past 64 000); in each, keep
 *    the up points of the lowest u (a share q = 5 % of them) and the down points of the highest w. Those
 *    are the exchanges whose delay came near its floor, so they scatter only over
 *    the bottom of the delay's range, not over all of it (a late ping, a backlog,
 *    does not pull them). A line fitted by least squares through the kept up points,
 *    and one through the kept down points, with one common slope and an intercept
 *    each, gives the slope correction s: r ← r + s. The slices keep the cut local,
 *    so a tilt of the current r barely changes which points are kept; three passes
 *    settle it. The two directions are weighted by the inverse of their residual
 *    variance (a jittery direction counts less).
 *    The last slice takes the remainder (64 to 127 exchanges), so a slice is never
 *    short. A short one's kept "edge" is merely its fastest of a few, or, alone, the
 *    one exchange whatever its delay: on a link that corrupts frames, a resent ping
 *    (stamped at its first copy, so 4 ms slow going up) alone in the newest slice
 *    pulled the least-squares rate from +6 to −22 ppm, and that refit moved the
 *    model 70 µs, back again at the next (fault matrix, corruption 10⁻², light
 *    painter seed 95; a motor of the Blot ran 1.655 steps behind its plan with seed
 *    78). Folded in, the same exchange is just a slow point, not kept.
 *    Why not the slices' extremes alone (one point per slice and direction, as this
 *    code did before): near its floor the delay's density grows linearly (a USB
 *    frame wait plus a jitter), so the few lowest points of a slice carry about as
 *    much as its lowest, so using them all uses more of the same exchanges (seed 1
 *    of bench/sync, motorB at 800 s: rate error 15 → 2 ns/s; worst p99 over seeds
 *    1–20: 12.6 → 8.5 µs). A rate error ε shows in the offset below as ε × the age of the
 *    envelope's points, up to the window (20 minutes): 10 ns/s there is 12 µs.
 * 2. The offset. The envelopes of every exchange in the window, at that rate:
 *    D(a₀) = (min u + max w)/2. The more exchanges, the nearer each envelope comes
 *    to its floor (on a link that also waits for 1 ms USB frames, only like 1/√n).
 * Until the window spans half a second the rate is held (1 at first) and only the
 * offset is fitted.
 *
 * ## Frames take time on a UART
 * On a board behind a USB–serial bridge (an Uno's 16U2) every byte also crosses a
 * UART, τ µs a byte (Link.uartByteTime_us: 40 µs at 250 000 baud), and a frame of L
 * bytes is whole only L·τ after its first byte left. The device stamps the PING when
 * its last byte (the delimiter) has come, and the PONG as its first byte goes; the
 * author reads the PONG once its last byte has come. With L↑, L↓ the two frames'
 * lengths and δ↑, δ↓ the delays that remain (USB frames, the bridge, the firmware's
 * loop):
 *   d₁ = D(a₁ + L↑·τ + δ↑)        a₂ = A(d₂) + L↓·τ + δ↓
 * so the stamps a₁′ = a₁ + L↑·τ and a₂′ = a₂ − L↓·τ are the symmetric exchange above,
 * and the fit takes those (PingStamps.pingOnWire_us, pongOnWire_us). Uncounted, the
 * up points sit r·L↑·τ higher and the down points r·L↓·τ lower, and the line midway
 * between them is off by (L↑ − L↓)·τ/2: a PING is 10 bytes and a PONG 16, so at
 * 40 µs a byte the device's clock looked 120 µs behind its true time, and every
 * segment started ~120 µs early (the emulated Uno's steps came 147 µs early; the
 * rest is the PONG's own wait in the Uno's transmit buffer and the PING's read
 * latency, which are not symmetric either; README, HIL). A native-USB board, and
 * the simulator's links, move a frame at once: τ is 0 there, nothing changes. The
 * round-trip time (rtt) stays the whole trip, wire times included: lead times need
 * all of it.
 *
 * ## Slewing: a refit moves the model by at most maxRefitMove_us
 * A segment's device time is fixed when it is sent, by the model then; it runs up to
 * a lead (tens of ms; longer for a long segment's end) later. A refit in between moves
 * the model by m at that time: the segment runs m off the model then in force. The
 * fault checks allow REFIT_US = 25 µs for that (core/system/harness.ts). A young
 * window's fit can jump by more: its envelopes rest on few exchanges, one new fast
 * exchange moves them, and its rate is still uncertain. On a link that corrupts 1 % of
 * bytes (a sixth of the exchanges lost), 2.2 s after begin(), the rate's standard
 * error (1/√(Σₖ wₖ·Sttₖ) in fitRate) was 11 ppm, the rate 28 ppm off, and one refit
 * moved the rate by 16 ppm and the offset by 62 µs (fault matrix, corruption 10⁻²,
 * light painter seed 15: a motor 0.26 steps beyond its bound).
 * So, once the model has a fitted rate, each refit takes the fit's rate but moves the
 * model's offset at the newest exchange, a₀, by at most S = maxRefitMove_us (10 µs)
 * towards the fit's; the rest follows at the next refits (NTP's slew, not its step).
 * A prediction t after a₀ then moves by at most S + |Δr|·t, Δr the rate's change (a
 * few ppm once the rate is fitted: < 1 µs over a 100 ms lead). Refits come every
 * 100 ms while the window is young (< 10 s), so a segment's span from its sending to
 * its end crosses one or two: 2·S = 20 µs < REFIT_US.
 * Convergence: a gap g between model and fit closes in ⌈g/S⌉ refits if the fit stays:
 * 100 µs a second while the window is young, 10 µs a second up to a minute, 1 µs a
 * second after (refits every 1 s, then 10 s), when refits move the fit by a few µs at
 * most. The rate is not slewed: held back, it would open the gap at |Δr| a second
 * (the model would fall behind faster than S a refit can follow). A fit more than
 * STEP_US (1 ms) away replaces the model at once: that is not a refit's noise, and
 * slewing it at 10 µs a step would take 100 refits. Before the rate is fitted (the
 * window's first half second, during begin()'s sync) every fit is taken whole.
 * errorEstimate_us adds the part not yet applied.
 *
 * The exchanges themselves: the session pings every 4 ms for its first two minutes,
 * then every 25 ms (session.ts).
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
  /** µs from the ping's first byte to its last on a UART (its length × the byte time; 0 or absent without a UART): see "Frames take time on a UART" */
  pingOnWire_us?: number;
  /** the same for the pong */
  pongOnWire_us?: number;
  /**
   * The ping was sent again (its first copy was corrupted, or its ack lost). It is
   * stamped at its first copy, so its round trip includes the resend's wait: not a
   * round trip of the link, and kept out of rtt and rttHigh (Karn's rule, as TCP
   * keeps resent segments out of its RTT). Its exchange still serves the fit: the up
   * point only looks slow, which the envelopes ignore.
   */
  resent?: boolean;
}

export interface ClockSyncOptions {
  /** fit over this much recent author time (µs) */
  window_us: number;
  /** hold the rate until the window spans this much (µs) */
  minSpanForRate_us: number;
  /** refit at most this often (µs) once the model exists */
  refitEvery_us: number;
  /** a refit moves the model's offset at the newest exchange by at most this (µs): see "Slewing" */
  maxRefitMove_us: number;
}

export const DEFAULT_CLOCK_SYNC: ClockSyncOptions = {
  window_us: 1_200_000_000,
  minSpanForRate_us: 500_000,
  refitEvery_us: 1_000_000,
  maxRefitMove_us: 10,
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
  /** The last fit had a fitted rate (not the held one): refits from then on are slewed. */
  private rateFitted = false;
  /** How far the model's offset is still from the last fit's (µs): the slew's part not yet applied. */
  private heldBack = 0;
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
    // The fit takes the stamps at the frames' far ends (see "Frames take time on a UART").
    this.a1.push(stamps.authorSend + (stamps.pingOnWire_us ?? 0));
    this.a2.push(stamps.authorReceive - (stamps.pongOnWire_us ?? 0));
    this.d1.push(d1);
    this.d2.push(d1 + held);
    this.samples++;
    if (!stamps.resent) {
      this.rttRecent.push(rtt);
      if (this.rttRecent.length > 64) this.rttRecent.shift();
    }

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
   * the last quarter of the window's exchanges were used, plus the part of the last
   * fit not yet applied (see "Slewing"). Infinity before a model.
   * It cannot see a constant asymmetry of the link (nothing can).
   */
  get errorEstimate_us(): number {
    return this.model === null ? Infinity : this.spread + this.heldBack;
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
    const rateFitted = span >= this.options.minSpanForRate_us && n >= 24;
    if (rateFitted) rate = fitRate(this.a1, this.d1, this.a2, this.d2, first, a0, rate);
    const offset = (envelope(up, rate, Math.min) + envelope(down, rate, Math.max)) / 2;
    const fitted = new ClockMap(a0, offset, rate);
    // Slew once the model has a fitted rate (segments are timed by it from then on).
    this.model = this.model !== null && this.rateFitted ? slewed(this.model, fitted, this.options.maxRefitMove_us) : fitted;
    this.heldBack = Math.abs(offset - this.model.deviceRef);
    this.rateFitted = rateFitted;
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

/** A fit further than this from the model (µs) replaces it at once: a slew would take too long (see "Slewing"). */
const STEP_US = 1_000;

/**
 * The fit, its offset at a₀ moved from the model's by at most `maxMove` (see "Slewing"
 * above): at a₀ the offset model(a₀) + clamp(fitted(a₀) − model(a₀), ±maxMove), the
 * fitted rate. A fit further than STEP_US replaces the model at once.
 */
function slewed(model: ClockMap, fitted: ClockMap, maxMove: number): ClockMap {
  const a0 = fitted.authorRef;
  const gap = fitted.deviceRef - model.toDeviceExact(a0);
  if (Math.abs(gap) > STEP_US) return fitted;
  return new ClockMap(a0, model.toDeviceExact(a0) + Math.max(-maxMove, Math.min(maxMove, gap)), fitted.rate);
}

/** Exchanges per slice in the rate fit, and the share of each slice kept per direction. */
const RATE_SLICE = 64;
const RATE_EDGE_SHARE = 0.05;
const RATE_PASSES = 3;

/**
 * The rate, refined from `rate` (see "The fit" above, part 1): in each slice of
 * exchanges from `first`, the up points with the lowest u = d₁ − r·(a₁ − a₀) and the
 * down points with the highest w = d₂ − r·(a₂ − a₀); then one least-squares slope
 * through both sets (an intercept each), each set weighted by 1/its residual
 * variance. With t = a − a₀ and sums over a set, centred on the set's means:
 *   slope of a set = Σ t·y / Σ t²,   common slope s = Σₖ wₖ·Σ t·y / Σₖ wₖ·Σ t².
 * The residual u is taken relative to the first exchange's, so the sums stay small
 * (a device clock reads up to 2³² µs, squares near 10¹⁹ would lose µs).
 */
function fitRate(a1: number[], d1: number[], a2: number[], d2: number[], first: number, a0: number, rate: number): number {
  const n = a1.length - first;
  const per = Math.max(RATE_SLICE, Math.ceil(n / 1000));
  const lowest = new Float64Array(Math.max(1, Math.round(2 * per * RATE_EDGE_SHARE)));
  for (let pass = 0; pass < RATE_PASSES; pass++) {
    const up = new LineSums();
    const down = new LineSums();
    const uRef = d1[first] - rate * (a1[first] - a0);
    const wRef = d2[first] - rate * (a2[first] - a0);
    for (let i = first, end = first; i < a1.length; i = end) {
      // The last slice takes the remainder too (per to 2·per − 1 exchanges): a slice is
      // never short (see fitRate's comment).
      end = a1.length - (i + per) < per ? a1.length : i + per;
      const m = end - i;
      const keep = Math.max(1, Math.round(m * RATE_EDGE_SHARE));
      const uCut = kthSmallest(lowest, keep, i, end, (j) => d1[j] - rate * (a1[j] - a0) - uRef);
      const wCut = -kthSmallest(lowest, keep, i, end, (j) => -(d2[j] - rate * (a2[j] - a0) - wRef));
      for (let j = i; j < end; j++) {
        const u = d1[j] - rate * (a1[j] - a0) - uRef;
        if (u <= uCut) up.add(a1[j] - a0, u);
        const w = d2[j] - rate * (a2[j] - a0) - wRef;
        if (w >= wCut) down.add(a2[j] - a0, w);
      }
    }
    const wUp = 1 / Math.max(1, up.residualVariance());
    const wDown = 1 / Math.max(1, down.residualVariance());
    const stt = wUp * up.stt() + wDown * down.stt();
    if (!(stt > 0)) break;
    rate += (wUp * up.sty() + wDown * down.sty()) / stt;
  }
  return rate;
}

/**
 * The k-th smallest of value(j) for j in [from, to), k ≤ buffer.length: the k smallest
 * so far are kept sorted in `buffer` (insertion, O((to − from)·k); k is a few here).
 */
function kthSmallest(buffer: Float64Array, k: number, from: number, to: number, value: (j: number) => number): number {
  let held = 0;
  for (let j = from; j < to; j++) {
    const x = value(j);
    if (held === k && x >= buffer[k - 1]) continue;
    let at = held < k ? held++ : k - 1;
    while (at > 0 && buffer[at - 1] > x) {
      buffer[at] = buffer[at - 1];
      at--;
    }
    buffer[at] = x;
  }
  return buffer[held - 1];
}

/** Running sums for a least-squares line y = c + s·t. */
class LineSums {
  private n = 0;
  private t = 0;
  private y = 0;
  private tt = 0;
  private ty = 0;
  private yy = 0;
  add(t: number, y: number): void {
    this.n++;
    this.t += t;
    this.y += y;
    this.tt += t * t;
    this.ty += t * y;
    this.yy += y * y;
  }
  /** Σ (t − t̄)² */
  stt(): number {
    return this.n === 0 ? 0 : this.tt - (this.t * this.t) / this.n;
  }
  /** Σ (t − t̄)(y − ȳ) */
  sty(): number {
    return this.n === 0 ? 0 : this.ty - (this.t * this.y) / this.n;
  }
  /** The scatter about the fitted line: Σ residual² / (n − 2). */
  residualVariance(): number {
    if (this.n < 3) return Infinity;
    const stt = this.stt();
    const sty = this.sty();
    const syy = this.yy - (this.y * this.y) / this.n;
    return Math.max(0, syy - (stt > 0 ? (sty * sty) / stt : 0)) / (this.n - 2);
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
