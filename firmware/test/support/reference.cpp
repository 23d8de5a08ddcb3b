#include "support/reference.h"

#include <algorithm>
#include <cmath>

namespace maxltest {

RefState referenceSigma(const maxl_fw::msg::TimingSegment& t, double tauUs) {
  double T = 0, q = 0, rest = 0;
  for (int k = 0; k < t.phaseCount; k++) T += t.durations[k] * 1e-6;
  for (int k = t.phaseCount - 1; k >= 0; k--) {
    int kind = (t.shape >> (2 * k)) & 3;
    int c = kind == 1 ? 1 : kind == 3 ? -1 : 0;
    double d = t.durations[k] * 1e-6;
    q += c * d * (d / 2 + rest);
    rest += d;
  }
  double alpha = t.alpha;
  double nu = (1 - alpha * q) / T;
  double sigma = 0, acc = 0;
  double tau = std::clamp(tauUs * 1e-6, 0.0, T);
  for (int k = 0; k < t.phaseCount; k++) {
    int kind = (t.shape >> (2 * k)) & 3;
    int c = kind == 1 ? 1 : kind == 3 ? -1 : 0;
    double d = t.durations[k] * 1e-6;
    double in = std::min(tau, d);
    acc = c * alpha;
    sigma += in * (nu + 0.5 * acc * in);
    nu += acc * in;
    if (tau < d || k + 1 == t.phaseCount) break;
    tau -= d;
  }
  return RefState{sigma, nu, acc};
}

// Error sources, in units (2^-16 mm), at τ µs into the segment:
//  - the two floors of each evaluation and the phase changes: < 8 units;
//  - B (velocity) rounded to 2^-17 units/µs, and shifted by up to 2^-15 per
//    phase change: < 2^-15·τ;
//  - C (half acceleration) rounded to 2^-33 units/µs²: < 2^-33·τ²;
//  - float (24-bit) ν0, α·Q and the coefficients: relative 2^-22 of the
//    travel Δ, twice over.
double positionToleranceUnits(double tauUs, double deltaUnits) {
  return 8.0 + std::ldexp(tauUs, -15) + std::ldexp(tauUs * tauUs, -33) + std::ldexp(std::fabs(deltaUnits), -21);
}

}  // namespace maxltest
