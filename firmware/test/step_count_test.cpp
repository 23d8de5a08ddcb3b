// countJump (readers/step_count.h): a stepper's count moved to a position in
// one pass must be the count found by walking the thresholds one at a time
// (each compared through its ceiling in whole units, as stepToward does), and
// the next threshold exactly U ± k·s. On the host countJump is the portable
// form; the AVR assembly is checked against the same portable form in simavr
// (firmware/bench/StepCountCheck, run by scripts/firmware-avr.sh); so is
// timesR (readers/step_times.h), tested here for what its portable form means.
#include <gtest/gtest.h>

#include <cstdint>

#include "maxl/readers/step_count.h"
#include "maxl/readers/step_generator.h"
#include "maxl/readers/step_times.h"
#include "maxl/motion/fixed_point.h"

using namespace maxl_fw;

namespace {

int64_t ceilQ16(int64_t x) { return x >= 0 ? (x + 65535) / 65536 : -((-x) / 65536); }

// Walks up to 200 thresholds: the count due at m, and the next upper threshold.
struct Walk {
  int k;
  int64_t next;
};
Walk walk(int32_t m, uint32_t sWhole, uint16_t sFrac, int64_t U, bool up) {
  const int64_t s = ((int64_t)sWhole << 16) | sFrac;
  int k = 0;
  if (up)
    while (k < 200 && ceilQ16(U + k * s) <= m) k++;
  else
    while (k < 200 && m < ceilQ16(U - (k + 1) * s)) k++;
  return {k, up ? U + k * s : U - k * s};
}

int counted = 0, beyond = 0;  // cases with 1..128 steps, with more

// One case: the walk's answer, or COUNT_NOT_HERE past 128 steps.
void check(int32_t m, uint32_t sWhole, uint16_t sFrac, int32_t upWhole, uint16_t upFrac, bool up) {
  ASSERT_TRUE(countJumpFits(m, upWhole, (int32_t)sWhole));
  const Walk w = walk(m, sWhole, sFrac, (int64_t)upWhole * 65536 + upFrac, up);
  uint32_t uw = (uint32_t)upWhole;
  uint16_t uf = upFrac;
  const uint8_t k = countJump(m, sWhole, sFrac, uw, uf, up);
  const char* dir = up ? "up" : "down";
  if (w.k > 128) {
    beyond++;
    ASSERT_EQ(k, COUNT_NOT_HERE) << dir << " m=" << m << " S=" << sWhole << " F=" << sFrac << " U=" << upWhole << ":" << upFrac;
    return;
  }
  ASSERT_EQ(k, w.k) << dir << " m=" << m << " S=" << sWhole << " F=" << sFrac << " U=" << upWhole << ":" << upFrac;
  if (k) {
    counted++;
    ASSERT_EQ((int64_t)(int32_t)uw * 65536 + uf, w.next)
        << dir << " m=" << m << " S=" << sWhole << " F=" << sFrac << " U=" << upWhole << ":" << upFrac;
  }
}

uint32_t rng = 12345;
uint32_t next32() {  // xorshift32
  rng ^= rng << 13;
  rng ^= rng >> 17;
  rng ^= rng << 5;
  return rng;
}

}  // namespace

// Every fraction of the threshold (every 7th), small step sizes at the edges
// of their whole and fractional parts, positions within 12 units either side:
// the exact ceilings (a threshold on a whole unit, just past one) and counts
// of 0 to past 128.
TEST(StepCount, SmallStepsEveryThresholdFraction) {
  const uint32_t wholes[] = {0, 1, 2, 3, 4};
  const uint16_t fracs[] = {0, 1, 0x7FFF, 0x8000, 0xFFFF};
  for (uint32_t S : wholes)
    for (uint16_t F : fracs) {
      if (!S && !F) continue;  // s >= 1
      for (uint32_t uf = 0; uf < 65536; uf += 7)
        for (int32_t off = -12; off <= 12; off++)
          for (int up = 0; up < 2; up++) check(1000 + off, S, F, 1000, (uint16_t)uf, up != 0);
    }
}

// Random step sizes from 2^-16 to 2^23 units (log-uniform), thresholds and
// positions anywhere in the domain, counts from 0 to past 128 and positions
// right at a threshold's ceiling or one unit short of it.
TEST(StepCount, RandomStepsAndPositionsMatchTheWalk) {
  counted = beyond = 0;
  for (int i = 0; i < 400000; i++) {
    const uint32_t bits = next32() % 39;  // s below 2^(bits + 1) in Q16, S below 2^23
    uint64_t sq = ((uint64_t)next32() << 32 | next32()) & ((2ull << bits) - 1);
    if (!sq) sq = 1;
    const uint32_t S = (uint32_t)(sq >> 16);
    const uint16_t F = (uint16_t)sq;
    const int32_t upWhole = (int32_t)(next32() % 0x3C000000u) - 0x1E000000;
    const uint16_t upFrac = (uint16_t)next32();
    const bool up = next32() & 1;
    const int64_t U = (int64_t)upWhole * 65536 + upFrac;
    const int64_t j = (int64_t)(next32() % 140);
    int64_t target;  // Q16
    switch (next32() % 3) {
      case 0:  // anywhere up to ~140 steps away
        target = up ? U + (int64_t)((double)(next32()) / 4294967296.0 * 140.0 * (double)sq)
                    : U - (int64_t)((double)(next32()) / 4294967296.0 * 140.0 * (double)sq);
        break;
      case 1:  // on threshold j's ceiling
        target = (up ? ceilQ16(U + j * (int64_t)sq) : ceilQ16(U - j * (int64_t)sq)) * 65536;
        break;
      default:  // a unit short of it
        target = (up ? ceilQ16(U + j * (int64_t)sq) - 1 : ceilQ16(U - j * (int64_t)sq) - 1) * 65536;
        break;
    }
    int64_t mw = target >= 0 ? target / 65536 : -((-target + 65535) / 65536);
    if (mw >= 0x20000000 || mw < -0x20000000) continue;
    check((int32_t)mw, S, F, upWhole, upFrac, up);
  }
  EXPECT_GT(counted, 200000);  // most cases count steps
  EXPECT_GT(beyond, 10000);    // and some are past 128
}

// Counts of exactly 128 and 129 steps: the last one counted here, the first not.
TEST(StepCount, OneHundredTwentyEightStepsAtMost) {
  const uint32_t S = 819;
  const uint16_t F = 12345;
  const int64_t s = ((int64_t)S << 16) | F;
  const int32_t upWhole = 5000;
  const uint16_t upFrac = 777;
  const int64_t U = (int64_t)upWhole * 65536 + upFrac;
  for (int k = 126; k <= 130; k++) {
    const int32_t m = (int32_t)ceilQ16(U + (k - 1) * s);  // exactly k due going up
    uint32_t uw = upWhole;
    uint16_t uf = upFrac;
    const uint8_t got = countJump(m, S, F, uw, uf, true);
    if (k <= 128)
      EXPECT_EQ(got, k);
    else
      EXPECT_EQ(got, COUNT_NOT_HERE);
  }
}

TEST(StepCount, DomainIsEightMetresAndStepsUnder128mm) {
  EXPECT_TRUE(countJumpFits(0x1FFFFFFF, -0x20000000, 0x7FFFFF));
  EXPECT_FALSE(countJumpFits(0x20000000, 0, 1));
  EXPECT_FALSE(countJumpFits(0, -0x20000001, 1));
  EXPECT_FALSE(countJumpFits(0, 0, 0x800000));
  EXPECT_FALSE(countJumpFits(0, 0, -1));
}

#if MAXL_STEP_TIMER
// The whole window (MAXL_StepGenerator::planWindow) by the one-pass count
// against the same window by the walk: twin generators whose positions differ
// by K whole steps (s a power of two units, so the shift is exact), the second
// 2^30 units or more from the origin, outside countJump's domain, so it walks.
// Their runs must be the same bit for bit, and their counts K apart, over
// windows of every kind (both ways, at rest, bursts after a lag change, over
// 127 steps, lengths not a power of two).
TEST(StepCount, WindowsMatchTheWalkingTwin) {
  long windows = 0, runs = 0;
  for (int trial = 0; trial < 600; trial++) {
    const int k = (int)(next32() % 13);  // s = 2^k units
    const int32_t s = (int32_t)1 << k;
    const float spm = 65536.0f / (float)s;
    const int32_t K = (int32_t)(((int64_t)1 << 30) / s + 1);
    const int32_t shift = K * s;
    MAXL_StepGenerator fast(2, 5, spm), walking(2, 5, spm);
    int32_t p = (int32_t)(next32() % 0x20000000u) - 0x10000000;
    fast.reference(p);
    walking.reference(p + shift);
    ASSERT_EQ(walking.steps() - fast.steps(), K);
    for (int i = 0; i < 60; i++) {
      const uint32_t kind = next32() % 16;
      const uint16_t w = kind == 0 ? (uint16_t)(1 + next32() % 4000) : (uint16_t)(128u << (next32() % 5));
      const int32_t maxSteps = kind == 1 ? 0 : kind == 2 ? 200 : kind == 3 ? 3 : 110;
      const int32_t delta = maxSteps ? (int32_t)((int64_t)((int32_t)(next32() % (2u * maxSteps + 1)) - maxSteps) * s +
                                                 (int32_t)(next32() % (uint32_t)s))
                                     : 0;
      const int32_t lag = kind == 4 ? (int32_t)(next32() % 4000) : (int32_t)(next32() % 40);
      MAXL_StepWindow a, b;
      fast.planWindow(w, p, p + delta, lag, a);
      walking.planWindow(w, p + shift, p + delta + shift, lag, b);
      ASSERT_EQ(a.runs, b.runs) << trial << " " << i;
      for (int r = 0; r < a.runs; r++) {
        ASSERT_EQ(a.run[r].first, b.run[r].first) << trial << " " << i << " run " << r;
        ASSERT_EQ(a.run[r].interval, b.run[r].interval) << trial << " " << i << " run " << r;
        ASSERT_EQ(a.run[r].count, b.run[r].count) << trial << " " << i << " run " << r;
        ASSERT_EQ(a.run[r].backward, b.run[r].backward) << trial << " " << i << " run " << r;
        runs++;
      }
      ASSERT_EQ(walking.steps() - fast.steps(), K) << trial << " " << i;
      windows++;
      p += delta;
      if (p > 0x18000000 || p < -0x18000000) break;
    }
  }
  EXPECT_GT(windows, 30000);     // few trials end early at the position bound
  EXPECT_GT(runs, windows / 2);  // most windows hold steps
}
#endif

// timesR (readers/step_times.h): the time x·r in Q16 µs from R = r·2^20 and
// x = whole + frac/2^16, never early: at least x·R/2^4 exactly (in rationals),
// at most 2 + 2^-4 above it (the two floors cost under 1 each, the + 2 makes
// them good); and equal to the form planWindow used before it was assembly
// (mulhi16 of R as a signed number, R < 2^31). Where whole·R does not fit 32
// bits (not where planWindow calls it) only the second property holds.
TEST(StepTimes, NeverEarlyAtMostTwoLateAndAsBefore) {
  uint64_t state = 88172645463325252ull;
  auto next = [&state]() {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return (uint32_t)(state >> 11);
  };
  int checked = 0;
  for (int i = 0; i < 400000; i++) {
    uint32_t r = (next() >> (next() % 32)) & 0x7FFFFFFFu;
    uint32_t whole = next() >> (next() % 32);
    uint16_t frac = (uint16_t)(next() >> (next() % 17));
    uint32_t t = timesRPortable(whole, frac, r);
    uint32_t before = ((whole * r) >> 4) + ((uint32_t)mulhi16((int32_t)r, frac) >> 4) + 2;
    ASSERT_EQ(t, before) << "whole " << whole << " frac " << frac << " r " << r;
    if ((uint64_t)whole * r >= (1ull << 32)) continue;
    // exact x·R/2^4 in units of 2^-20: (whole·2^16 + frac)·R
    const unsigned __int128 exact = ((unsigned __int128)whole * 65536u + frac) * r;  // /2^20 is x·R/2^4
    const unsigned __int128 got = (unsigned __int128)t << 20;
    ASSERT_GE(got, exact) << "early: whole " << whole << " frac " << frac << " r " << r;
    ASSERT_LE(got - exact, ((unsigned __int128)2 << 20) + ((unsigned __int128)1 << 16)) << "late: whole " << whole;
    checked++;
  }
  EXPECT_GT(checked, 100000);
}
