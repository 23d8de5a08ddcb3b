// The fixed-point kernel of the evaluation hot path (motion/fixed_point.h).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "maxl/motion/fixed_point.h"

using namespace maxl_fw;

namespace {
int64_t floorDiv65536(__int128 v) {
  __int128 q = v / 65536;
  if (v % 65536 != 0 && v < 0) q--;
  return (int64_t)q;
}
}  // namespace

TEST(FixedPoint, MulHi16IsTheExactFloor) {
  std::mt19937_64 rng(3);
  const int32_t edges[] = {0, 1, -1, 65535, 65536, -65536, INT32_MAX, INT32_MIN, 0x7FFF0000, -0x7FFF0001};
  const uint16_t xs[] = {0, 1, 2, 32767, 32768, 65535};
  for (int32_t a : edges)
    for (uint16_t x : xs) ASSERT_EQ(mulhi16(a, x), floorDiv65536((__int128)a * x)) << a << " " << x;
  for (int i = 0; i < 200000; i++) {
    int32_t a = (int32_t)rng();
    uint16_t x = (uint16_t)rng();
    ASSERT_EQ(mulhi16(a, x), floorDiv65536((__int128)a * x));
  }
}

// p(x) = P + B·x/2^16 + C·x²/2^32, exactly, in units.
static double exact(const FixedTrack& t, double x) {
  return t.P + t.B * x / 65536.0 + t.C * x * x / 4294967296.0;
}

TEST(FixedPoint, EvaluationWithinTwoUnitsOfTheQuadratic) {
  std::mt19937 rng(4);
  for (int i = 0; i < 20000; i++) {
    FixedTrack t;
    t.P = (int32_t)(rng() % 2000000000) - 1000000000;
    t.B = (int32_t)(rng() % 200000000) - 100000000;  // ±1500 units/µs (±23 m/s)
    t.C = (int32_t)(rng() % 20000000) - 10000000;
    uint16_t x = (uint16_t)rng();
    double e = exact(t, x);
    int32_t got = t.at(x);
    ASSERT_LE(std::fabs(got - e), 2.0) << t.P << " " << t.B << " " << t.C << " " << x;
  }
}

TEST(FixedPoint, NextChunkIsExact) {
  // Moving the chunk start by 2^16 µs must not change any later value.
  FixedTrack t{12345, 3 * 65536 + 777, -4567};
  FixedTrack moved = t;
  moved.nextChunk();
  for (uint32_t y : {0u, 1u, 1000u, 65535u}) {
    double e = exact(t, 65536.0 + y);
    double f = exact(moved, y);
    EXPECT_DOUBLE_EQ(e, f) << y;
  }
}

TEST(FixedPoint, AdvanceKeepsPositionAndVelocityContinuous) {
  FixedTrack t{-5000, 200000, 3000};
  for (uint16_t x : {1, 333, 40000, 65535}) {
    FixedTrack a = t;
    a.advance(x);
    EXPECT_NEAR(a.P, exact(t, x), 2.0);
    // velocity in Q16.16: B + 2·C·x/2^16
    EXPECT_NEAR(a.B, t.B + 2.0 * t.C * x / 65536.0, 2.0);
    EXPECT_EQ(a.C, t.C);
  }
}
