// Float maths of protocol §5 and §6 (motion/profile.h).
#include <gtest/gtest.h>

#include <cmath>

#include "maxl/motion/profile.h"
#include "support/author.h"
#include "support/reference.h"

using namespace maxl_fw;

namespace {
Segment segmentOf(const msg::TimingSegment& t) {
  Segment s{};
  s.shape = t.shape;
  s.phaseCount = t.phaseCount;
  for (int k = 0; k < 3; k++) s.durations[k] = t.durations[k];
  s.alpha = t.alpha;
  return s;
}
}  // namespace

TEST(Profile, Nu0FollowsFromSigmaOfTEqualsOne) {
  // 100 mm from rest to rest at 3000 mm/s², cruise 200 mm/s.
  msg::TimingSegment t = maxltest::trapezoid(100.0, 0, 200, 0, 3000);
  Segment s = segmentOf(t);
  float peak, end;
  ASSERT_TRUE(solveProfile(s, peak, end));
  EXPECT_NEAR(s.nu0, 0.0, 1e-5);          // starts at rest
  EXPECT_NEAR(peak * 100.0, 200.0, 0.05);  // cruise at 200 mm/s
  EXPECT_NEAR(end * 100.0, 0.0, 0.02);     // ends at rest (rounding of durations)
  float sigma, nu, acc;
  sigmaAt(s, s.duration(), sigma, nu, acc);
  EXPECT_NEAR(sigma, 1.0, 1e-6);
  maxltest::RefState r = maxltest::referenceSigma(t, s.duration() / 3.0);
  sigmaAt(s, s.duration() / 3, sigma, nu, acc);
  EXPECT_NEAR(sigma, r.sigma, 2e-6);
  EXPECT_NEAR(nu, r.nu, 1e-5);
}

TEST(Profile, RejectsUnrunnableTiming) {
  float peak, end;
  Segment s{};
  EXPECT_FALSE(solveProfile(s, peak, end));  // no phase
  s.shape = phase::CRUISE;
  s.phaseCount = 1;
  s.durations[0] = 0;
  s.length = 1.0f;
  EXPECT_FALSE(solveProfile(s, peak, end));  // T = 0 for a segment that moves
  s.durations[0] = 0x80000000u;
  EXPECT_FALSE(solveProfile(s, peak, end));  // not wrap-safe
  s.durations[0] = 1000;
  s.alpha = -1.0f;
  EXPECT_FALSE(solveProfile(s, peak, end));
  s.alpha = NAN;
  EXPECT_FALSE(solveProfile(s, peak, end));
  s.alpha = 0.0f;
  EXPECT_TRUE(solveProfile(s, peak, end));
  EXPECT_NEAR(s.nu0, 1000.0, 1e-3);  // 1/T
  // Decelerating so hard the speed would go negative: refused.
  s.shape = phase::DECELERATE;
  s.durations[0] = 1000000;
  s.alpha = 10.0f;  // ν0 = (1 + 10/2)/1 = 6, end = 6 - 10 = -4
  EXPECT_FALSE(solveProfile(s, peak, end));
}

TEST(Profile, BrakeStopsOrLeaves) {
  BrakePiece stop = planBrake(100.0f, 1000.0f, 10.0f);  // needs 5 mm
  EXPECT_TRUE(stop.stops);
  EXPECT_NEAR(stop.distance, 5.0f, 1e-5);
  EXPECT_EQ(stop.duration, 100000u);
  BrakePiece leave = planBrake(100.0f, 1000.0f, 3.2f);
  EXPECT_FALSE(leave.stops);
  EXPECT_NEAR(leave.exitSpeed, 60.0f, 1e-3);  // √(10000 − 6400)
  EXPECT_EQ(leave.duration, 40000u);          // (100 − 60)/1000 s
}

TEST(Profile, SlotCoefficientsScale) {
  int32_t b0, cmag;
  // 10 mm at ν0 = 2/s: 20 mm/s = 1310720 units/s = 1.31072 units/µs -> Q16: 85899
  ASSERT_TRUE(slotCoefficients(655360.0f, 2.0f, 2.0f, 0.0f, b0, cmag));
  EXPECT_EQ(b0, 85899);
  EXPECT_EQ(cmag, 0);
  EXPECT_FALSE(slotCoefficients(2e9f, 1e6f, 1e6f, 0.0f, b0, cmag));  // far over 250 m/s
}

// A dwell (length 0): σ still runs 0..1 over T, so ν0 = 1/T; an instant
// (T = 0) is allowed for a dwell only, and solves to ν0 = 0.
TEST(Profile, DwellsAndInstants) {
  float peak, end;
  Segment s{};
  s.shape = phase::CRUISE;
  s.phaseCount = 1;
  s.durations[0] = 120000;
  s.length = 0.0f;
  ASSERT_TRUE(solveProfile(s, peak, end));
  EXPECT_NEAR(s.nu0, 1.0f / 0.12f, 1e-3);
  EXPECT_NEAR(end, s.nu0, 1e-6);
  s.durations[0] = 0;
  ASSERT_TRUE(solveProfile(s, peak, end));
  EXPECT_EQ(s.nu0, 0.0f);
  EXPECT_EQ(peak, 0.0f);
  EXPECT_EQ(end, 0.0f);
  s.alpha = NAN;  // still refused: a bad α is bad on any segment
  EXPECT_FALSE(solveProfile(s, peak, end));
}
