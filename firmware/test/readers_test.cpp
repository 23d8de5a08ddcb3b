// Reader classes: the step generator, position deltas, sensor writers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "support/harness.h"
#include "support/reference.h"

using namespace maxl_fw;
using namespace maxltest;

namespace {

struct PinCount {
  int rising = 0;
  int dirChanges = 0;
  int lastDir = -1;
};

PinCount countPins(uint8_t stepPin, uint8_t dirPin) {
  PinCount c;
  const host::PinWrite* log = host::pinLog();
  int last = 0;
  for (size_t i = 0; i < host::pinLogLength(); i++) {
    if (log[i].pin == stepPin) {
      if (log[i].value && !last) c.rising++;
      last = log[i].value;
    } else if (log[i].pin == dirPin) {
      if (c.lastDir != log[i].value) c.dirChanges++;
      c.lastDir = log[i].value;
    }
  }
  return c;
}
}  // namespace

TEST(StepGenerator, ReferenceDoesNotStep) {
  host::reset();
  MAXL_StepGenerator g(2, 5, 80.0f);
  g.reference(mm(10.0));
  EXPECT_EQ(g.steps(), 800);
  g.reference(mm(-0.01));
  EXPECT_EQ(g.steps(), -1);  // -0.8 steps rounds to -1
  EXPECT_EQ(countPins(2, 5).rising, 0);
}

TEST(StepGenerator, EmitsEveryDueStepInOneCall) {
  host::reset();
  MAXL_StepGenerator g(2, 5, 80.0f);
  g.reference(0);
  // 800 steps due at once: MAXL_MAX_STEPS_PER_EVALUATION per call, all emitted.
  int calls = 1;
  while (!g.moveTo(mm(10.0))) calls++;
  EXPECT_EQ(calls, (800 + MAXL_MAX_STEPS_PER_EVALUATION - 1) / MAXL_MAX_STEPS_PER_EVALUATION);
  EXPECT_EQ(g.steps(), 800);
  PinCount c = countPins(2, 5);
  EXPECT_EQ(c.rising, 800);
  EXPECT_EQ(c.lastDir, 1);
  while (!g.moveTo(mm(9.0))) {
  }
  EXPECT_EQ(g.steps(), 720);
  c = countPins(2, 5);
  EXPECT_EQ(c.rising, 880);
  EXPECT_EQ(c.lastDir, 0);
  EXPECT_EQ(c.dirChanges, 2);
}

TEST(StepGenerator, InvertedDirection) {
  host::reset();
  MAXL_StepGenerator g(3, 6, 100.0f, true);
  g.reference(0);
  while (!g.moveTo(mm(1.0))) {
  }
  EXPECT_EQ(countPins(3, 6).lastDir, 0);
  g.moveTo(mm(0.0));
  EXPECT_EQ(countPins(3, 6).lastDir, 1);
}

TEST(StepGenerator, StepsAreRoundedPositionsAndNeverDrift) {
  host::reset();
  MAXL_StepGenerator g(2, 5, 78.74f);  // steps/mm of a 1.8° motor on a GT2-20 at 1/8 (not a nice number)
  g.reference(0);
  double s = 65536.0 / 78.74;          // units per step, as the generator's Q16 value rounds it
  int32_t p = 0;
  uint32_t rng = 12345;
  for (int i = 0; i < 200000; i++) {
    rng = rng * 1103515245u + 12345u;
    p += (int32_t)((rng >> 16) % 4001) - 2000;
    while (!g.moveTo(p)) {
    }
    double n = std::floor(p / s + 0.5);
    ASSERT_NEAR(g.steps(), n, 1.0) << i;  // equal except within rounding of s of a threshold
    if (std::fabs(p / s + 0.5 - std::round(p / s + 0.5)) > 1e-3) {
      ASSERT_EQ(g.steps(), (int32_t)n) << i;
    }
  }
  EXPECT_EQ(countPins(2, 5).rising >= std::abs(g.steps()), true);
}

// The step a position rounds to, in exact integer arithmetic from the
// generator's own step size sQ = s·2^16 (as its constructor rounds it): the
// upper threshold of step n is U_n = (n·sQ + floor(sQ/2)) / 2^16, and the
// count is the least n with p < U_n.
int64_t exactStep(float stepsPerMm, int32_t p) {
  int64_t sQ = (int64_t)(4294967296.0f / stepsPerMm);
  int64_t num = (int64_t)p * 65536 - sQ / 2;
  int64_t q = num >= 0 ? num / sQ : -((-num + sQ - 1) / sQ);  // floor
  return q + 1;
}

// Long moves take most of their steps in jumps (stepToward): after every move
// the count must be exactly the step the position rounds to, for step sizes
// from a fraction of a unit to many thousands of units, with one STEP pulse
// per step; reference() must find the same from anywhere.
TEST(StepGenerator, LongMovesLandOnTheExactStep) {
  const float stepsPerMm[] = {0.37f, 1.0f, 3.0f, 78.74f, 80.0f, 400.0f, 3200.0f, 65536.0f, 100000.0f};
  uint32_t rng = 777;
  for (float spm : stepsPerMm) {
    host::reset();
    MAXL_StepGenerator g(2, 5, spm);
    MAXL_StepGenerator other(3, 6, spm);
    g.reference(0);
    int32_t p = 0;
    int32_t emitted = 0;
    double unitsPerStep = 65536.0 / spm;
    for (int i = 0; i < 3000; i++) {
      rng = rng * 1103515245u + 12345u;
      // up to ~300 steps either way, and sometimes a fraction of one
      double span = (i % 5 == 0) ? unitsPerStep : 300.0 * unitsPerStep;
      double jumpUnits = ((double)(rng >> 8) / (double)(1u << 24) * 2.0 - 1.0) * span;
      if (std::fabs(p + jumpUnits) > 1.5e9) jumpUnits = -jumpUnits;
      p += (int32_t)jumpUnits;
      int32_t before = g.steps();
      int calls = 0;
      while (!g.moveTo(p)) ASSERT_LT(++calls, 100000) << spm;
      emitted += std::abs(g.steps() - before);
      ASSERT_EQ(g.steps(), exactStep(spm, p)) << "steps/mm " << spm << " move " << i << " to " << p;
      if (i % 7 == 0) {
        other.reference(i % 2 ? p : -p);  // from wherever it was
        ASSERT_EQ(other.steps(), exactStep(spm, i % 2 ? p : -p)) << spm;
      }
    }
    EXPECT_EQ(countPins(2, 5).rising, emitted) << spm;
    // far away at once, both ways (as far as the count fits in 31 bits)
    int32_t reach = (int32_t)std::min(1.5e9, 1e9 * unitsPerStep);
    for (int32_t far : {reach, -reach, 7, -7, 0}) {
      other.reference(far);
      EXPECT_EQ(other.steps(), exactStep(spm, far)) << spm << " " << far;
    }
  }
}

TEST(Stepper, FollowsATrajectoryStepForStep) {
  MAXL_Stepper stepper("stepper", 2, 5, 80.0f);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  std::vector<int32_t> p0 = {mm(5)};
  msg::TimingSegment t = trapezoid(20.0, 0, 150, 0, 2000);
  EXPECT_EQ(h.exchange(h.author.geometry(0, &p0, {{20.0f, {mm(25)}}}, 1)).reason, 0);
  uint32_t start = 10000;
  EXPECT_EQ(h.exchange(h.author.timing(0, 2000.0f, &start, {t})).reason, 0);
  host::clearPinLog();
  h.loopAt(5000);
  EXPECT_EQ(stepper.steps(), 400);  // referenced at 5 mm
  for (uint32_t now = 5000; now < start + durationOf(t) + 1000; now += 37) {
    h.loopAt(now);
    double tau = (double)(int32_t)(now - start);
    double expected = 5 + 20 * (tau < 0 ? 0 : referenceSigma(t, tau).sigma);
    ASSERT_NEAR(stepper.steps(), expected * 80, 0.52) << now;
  }
  EXPECT_EQ(stepper.steps(), 2000);
  EXPECT_EQ(countPins(2, 5).rising, 1600);
}

namespace {
std::vector<uint8_t> gChannels;
}

TEST(SensorWriter, BatchesSamplesStampedWithTheDeviceClock) {
  MAXL_SensorWriter accel("accel", 3);
  Harness h;
  float xyz[3] = {1.0f, 2.0f, 3.0f};
  EXPECT_FALSE(accel.write(xyz));  // not subscribed: nothing to send
  h.open({{0, kind::SENSOR, 0}});
  EXPECT_FALSE(h.device->idle());  // a subscribed sensor keeps the device awake
  // 3 channels: 1 + 12 bytes per sample (dt < 128 µs), 52 bytes per batch -> 4 samples.
  for (int i = 0; i < 9; i++) {
    h.at(1000 + i * 100);
    xyz[0] = (float)i;
    EXPECT_TRUE(accel.write(xyz));
  }
  std::vector<Packet> p = h.take();
  ASSERT_EQ(p.size(), 2u);  // two full batches; the ninth sample waits
  for (int b = 0; b < 2; b++) {
    ASSERT_EQ(p[b].type, type::SAMPLES);
    msg::SamplesView v;
    ASSERT_TRUE(v.parse(p[b].payload.data(), (uint8_t)p[b].payload.size(), 3));
    EXPECT_EQ(v.reader, 0);
    EXPECT_EQ(v.sampleSeq, b);
    EXPECT_EQ(v.count, 4);
    EXPECT_EQ(v.t0, 1000u + b * 400);
    uint32_t dt;
    float values[3];
    for (int k = 0; k < 4; k++) {
      v.next(dt, values);
      EXPECT_EQ(dt, k ? 100u : 0u);
      EXPECT_EQ(values[0], (float)(b * 4 + k));
      EXPECT_EQ(values[2], 3.0f);
    }
  }
  // The ninth goes out once it is MAXL_SAMPLE_MAX_AGE_US old.
  h.loopAt(1800 + MAXL_SAMPLE_MAX_AGE_US - 1);
  EXPECT_TRUE(h.take().empty());
  h.loopAt(1800 + MAXL_SAMPLE_MAX_AGE_US);
  p = h.take();
  ASSERT_EQ(p.size(), 1u);
  msg::SamplesView v;
  ASSERT_TRUE(v.parse(p[0].payload.data(), (uint8_t)p[0].payload.size(), 3));
  EXPECT_EQ(v.count, 1);
  EXPECT_EQ(v.sampleSeq, 2);
  EXPECT_EQ(v.t0, 1800u);
}

TEST(SensorWriter, LongGapsUseLongerVarints) {
  MAXL_SensorWriter one("one", 1);
  Harness h;
  h.open({{0, kind::SENSOR, 0}});
  float v = 0;
  h.at(0);
  one.writeAt(0, &v);
  one.writeAt(70000, &v);       // dt 70 000: 3-byte varint
  one.writeAt(4000070000u, &v);  // dt ~4e9: 5-byte varint
  one.flush();
  std::vector<Packet> p = h.take();
  ASSERT_EQ(p.size(), 1u);
  msg::SamplesView view;
  ASSERT_TRUE(view.parse(p[0].payload.data(), (uint8_t)p[0].payload.size(), 1));
  uint32_t dt;
  float values[1];
  view.next(dt, values);
  view.next(dt, values);
  EXPECT_EQ(dt, 70000u);
  view.next(dt, values);
  EXPECT_EQ(dt, 4000000000u);
}
