/**
 * How far a measured signal lags a planned one, by cross-correlation, and the RMS of
 * their difference.
 *
 * Both are sampled on one uniform grid (period T). For a shift of k samples the
 * normalised correlation over the points valid in both is
 *
 *   ρ(k) = Σₙ p̃[n]·m̃[n + k] / √(Σ p̃[n]² · Σ m̃[n + k]²),   p̃, m̃ with their means removed
 *
 * and the lag is the k that maximises ρ, refined by a parabola through ρ(k−1), ρ(k),
 * ρ(k+1): δ = ½(ρ₋ − ρ₊)/(ρ₋ − 2ρ₀ + ρ₊), lag = (k + δ)·T. A positive lag means the
 * measurement comes after the plan. Direct sums over |k| ≤ maxLag/T: a few hundred
 * shifts of a few thousand points, cheaper than an FFT for so few shifts, and exact.
 *
 * The lag between planned and measured acceleration includes the plant's own dynamics
 * (a belt spring delays and rings), so it is information for the user, not a clock
 * error.
 */

export interface LagEstimate {
  lag_s: number;
  /** ρ at the best whole shift, −1 … 1 */
  correlation: number;
}

/**
 * The lag of `measured` behind `planned` (same grid, period `period_s`), searched over
 * ±maxLag_s; `valid[n]` false marks points to leave out (a gap). Null if no shift has
 * enough overlap.
 */
export function crossCorrelationLag(
  planned: ArrayLike<number>,
  measured: ArrayLike<number>,
  period_s: number,
  maxLag_s: number,
  valid?: ArrayLike<boolean>,
): LagEstimate | null {
  const n = Math.min(planned.length, measured.length);
  const maxShift = Math.min(n - 2, Math.max(1, Math.round(maxLag_s / period_s)));
  const ok = (i: number) => valid === undefined || valid[i];
  const rho = (k: number): number => {
    // Means over the overlap, then the normalised sum.
    let sp = 0;
    let sm = 0;
    let count = 0;
    for (let i = Math.max(0, -k); i < n && i + k < n; i++) {
      if (!ok(i) || !ok(i + k)) continue;
      sp += planned[i];
      sm += measured[i + k];
      count++;
    }
    if (count < 3) return NaN;
    const mp = sp / count;
    const mm = sm / count;
    let spm = 0;
    let spp = 0;
    let smm = 0;
    for (let i = Math.max(0, -k); i < n && i + k < n; i++) {
      if (!ok(i) || !ok(i + k)) continue;
      const p = planned[i] - mp;
      const m = measured[i + k] - mm;
      spm += p * m;
      spp += p * p;
      smm += m * m;
    }
    return spp > 0 && smm > 0 ? spm / Math.sqrt(spp * smm) : NaN;
  };
  const values = new Map<number, number>();
  let best = NaN;
  let bestK = 0;
  for (let k = -maxShift; k <= maxShift; k++) {
    const r = rho(k);
    values.set(k, r);
    if (!Number.isNaN(r) && (Number.isNaN(best) || r > best)) {
      best = r;
      bestK = k;
    }
  }
  if (Number.isNaN(best)) return null;
  const r0 = values.get(bestK - 1) ?? NaN;
  const r2 = values.get(bestK + 1) ?? NaN;
  let delta = 0;
  const curve = r0 - 2 * best + r2;
  if (Number.isFinite(curve) && curve < 0) delta = Math.max(-0.5, Math.min(0.5, (0.5 * (r0 - r2)) / curve));
  return { lag_s: (bestK + delta) * period_s, correlation: best };
}

/** √(mean (a − b)²) over the points valid in both. */
export function rmsDifference(a: ArrayLike<number>, b: ArrayLike<number>, valid?: ArrayLike<boolean>): number {
  let sum = 0;
  let count = 0;
  for (let i = 0; i < Math.min(a.length, b.length); i++) {
    if (valid && !valid[i]) continue;
    sum += (a[i] - b[i]) ** 2;
    count++;
  }
  return count > 0 ? Math.sqrt(sum / count) : NaN;
}
