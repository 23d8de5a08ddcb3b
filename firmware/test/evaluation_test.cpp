// Segment evaluation (protocol §5) against an independent double-precision
// reference, within the documented tolerance (support/reference.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "support/harness.h"
#include "support/reference.h"

using namespace maxl_fw;
using namespace maxltest;

namespace {
double gPosition = 0, gDeltaSum = 0;
int gCalls = 0;
void onPosition(float position, float delta) {
  gPosition = position;
  gDeltaSum += delta;
  gCalls++;
}
float gRate = -1, gAccel = -1;
void onRate(float r) { gRate = r; }
void onAccel(float a) { gAccel = a; }


struct Planned {
  uint32_t start;
  msg::TimingSegment timing;
  std::vector<int32_t> p0, p1;
  double length;
};

// Runs the device from `from` to `to` in steps of `step` µs and checks every
// active slot against p0 + Δ·σ(t) of the segment running at t.
void checkPositions(Harness& h, const std::vector<Planned>& plan, uint32_t from, uint32_t to, uint32_t step) {
  for (uint32_t t = from; (int32_t)(t - to) <= 0; t += step) {
    h.loopAt(t);
    const Planned* seg = nullptr;
    for (auto& p : plan)
      if ((int32_t)(t - p.start) >= 0) seg = &p;
    for (size_t i = 0; i < plan[0].p0.size(); i++) {
      double expected, tolerance;
      if (!seg) {
        expected = plan[0].p0[i];
        tolerance = 0;
      } else {
        double tau = (double)(int32_t)(t - seg->start);
        RefState r = referenceSigma(seg->timing, tau);
        double delta = (double)seg->p1[i] - seg->p0[i];
        expected = seg->p0[i] + delta * r.sigma;
        tolerance = positionToleranceUnits(std::min<double>(tau, durationOf(seg->timing)), delta);
      }
      ASSERT_NEAR(h.device->positionUnits((uint8_t)i), expected, tolerance) << "t=" << t << " slot " << i;
    }
  }
}
}  // namespace

TEST(Evaluation, OneTrapezoidSegmentFollowsTheSpec) {
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  Planned seg{1000000, trapezoid(100.0, 0, 200, 0, 3000), {mm(10)}, {mm(110)}, 100.0};
  ASSERT_EQ(seg.timing.phaseCount, 3);
  EXPECT_EQ(h.exchange(h.author.geometry(0, &seg.p0, {{100.0f, seg.p1}}, 1)).reason, 0);
  EXPECT_EQ(h.exchange(h.author.timing(0, 3000.0f, &seg.start, {seg.timing})).reason, 0);
  gDeltaSum = 0;
  gCalls = 0;
  h.loopAt(900000);
  EXPECT_EQ(gPosition, 10.0);  // the reference position, reported with delta 0
  EXPECT_EQ(gDeltaSum, 0.0);
  uint32_t end = seg.start + durationOf(seg.timing);
  checkPositions(h, {seg}, 990000, end + 20000, 997);
  EXPECT_EQ(h.device->positionUnits(0), mm(110));  // exactly p1 at the end
  EXPECT_EQ(gPosition, 110.0);
  EXPECT_NEAR(gDeltaSum, 100.0, 1e-3);  // deltas add up to the move
  EXPECT_GT(gCalls, 500);
  EXPECT_EQ(h.device->state(), state::IDLE);
  EXPECT_FALSE(h.device->statusFlags() & status_flag::STARVED);  // it ended at rest
}

TEST(Evaluation, EveryMicrosecondOfAShortSegment) {
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  Planned seg{200, trapezoid(0.5, 0, 100, 0, 5000), {mm(-3)}, {mm(-3.5)}, 0.5};
  EXPECT_EQ(h.exchange(h.author.geometry(0, &seg.p0, {{0.5f, seg.p1}}, 1)).reason, 0);
  EXPECT_EQ(h.exchange(h.author.timing(0, 5000.0f, &seg.start, {seg.timing})).reason, 0);
  checkPositions(h, {seg}, 200, 200 + durationOf(seg.timing) + 10, 1);
}

TEST(Evaluation, ContiguousSegmentsAndTwoSlots) {
  // A CoreXY-like pair of actuator tracks: a = x + y, b = x − y.
  MAXL_TrackPositionLinear a("a", onPosition);
  MAXL_TrackPositionLinear b("b", onPosition);
  Harness h;
  h.open({{0, kind::POSITION, 0}, {1, kind::POSITION, 1}});
  struct Move {
    double x, y, ve, vx;
  } moves[] = {{10, 5, 0, 80}, {25, 5, 80, 60}, {25, -20, 60, 0}};
  double x = 0, y = 0;
  std::vector<Planned> plan;
  std::vector<GeometrySegment> geometry;
  std::vector<msg::TimingSegment> timing;
  uint32_t t = 2000000;
  for (auto& m : moves) {
    double L = std::hypot(m.x - x, m.y - y);
    Planned p{t, trapezoid(L, m.ve, 150, m.vx, 2000), {mm(x + y), mm(x - y)}, {mm(m.x + m.y), mm(m.x - m.y)}, L};
    plan.push_back(p);
    geometry.push_back({(float)L, p.p1});
    timing.push_back(p.timing);
    t += durationOf(p.timing);
    x = m.x;
    y = m.y;
  }
  EXPECT_EQ(h.exchange(h.author.geometry(0, &plan[0].p0, geometry, 2)).reason, 0);
  EXPECT_EQ(h.exchange(h.author.timing(0, 2000.0f, &plan[0].start, timing)).reason, 0);
  checkPositions(h, plan, 1990000, t + 10000, 331);
  EXPECT_EQ(h.device->positionUnits(0), mm(5));
  EXPECT_EQ(h.device->positionUnits(1), mm(45));
  EXPECT_EQ(h.device->state(), state::IDLE);
}

TEST(Evaluation, LongPhasesStayWithinTolerance) {
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  // 2 s accelerating at 50 mm/s² to 100 mm/s, 8 s cruising, 2 s braking: 1000 mm.
  Planned seg{5000, trapezoid(1000.0, 0, 100, 0, 50), {mm(0)}, {mm(1000)}, 1000.0};
  EXPECT_EQ(h.exchange(h.author.geometry(0, &seg.p0, {{1000.0f, seg.p1}}, 1)).reason, 0);
  EXPECT_EQ(h.exchange(h.author.timing(0, 50.0f, &seg.start, {seg.timing})).reason, 0);
  checkPositions(h, {seg}, 0, seg.start + durationOf(seg.timing) + 100000, 9973);
  EXPECT_EQ(h.device->positionUnits(0), mm(1000));
}

TEST(Evaluation, SparseLoopCallsCrossManyBoundaries) {
  // loop() called only every 0.3 s: each call crosses chunks, phases and segments.
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  std::vector<Planned> plan;
  std::vector<GeometrySegment> geometry;
  std::vector<msg::TimingSegment> timing;
  uint32_t t = 100000;
  for (int k = 0; k < 6; k++) {
    Planned p{t, trapezoid(20.0, k ? 50 : 0, 50, k == 5 ? 0 : 50, 1000), {mm(20.0 * k)}, {mm(20.0 * (k + 1))}, 20.0};
    plan.push_back(p);
    geometry.push_back({20.0f, p.p1});
    timing.push_back(p.timing);
    t += durationOf(p.timing);
  }
  EXPECT_EQ(h.exchange(h.author.geometry(0, &plan[0].p0, geometry, 1)).reason, 0);
  // Three segments per TIMING frame (a frame holds 60 bytes of payload).
  std::vector<msg::TimingSegment> firstHalf(timing.begin(), timing.begin() + 3), secondHalf(timing.begin() + 3, timing.end());
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &plan[0].start, firstHalf)).reason, 0);
  EXPECT_EQ(h.exchange(h.author.timing(3, 1000.0f, nullptr, secondHalf)).reason, 0);
  checkPositions(h, plan, 0, t + 300000, 300007);
  EXPECT_EQ(h.device->positionUnits(0), mm(120));
}

TEST(Evaluation, VelocityAndAccelerationReaders) {
  MAXL_TrackVelocity v("v", onRate);
  MAXL_TrackAcceleration acc("a", onAccel);
  Harness h;
  h.open({{0, kind::VELOCITY, 0}, {1, kind::ACCELERATION, 0}});
  msg::TimingSegment timing = trapezoid(50.0, 0, 120, 0, 1500);
  uint32_t start = 10000;
  std::vector<int32_t> none;
  EXPECT_EQ(h.exchange(h.author.geometry(0, &none, {{50.0f, {}}}, 0)).reason, 0);
  EXPECT_EQ(h.exchange(h.author.timing(0, 1500.0f, &start, {timing})).reason, 0);
  h.loopAt(5000);
  EXPECT_EQ(gRate, 0.0f);
  EXPECT_EQ(gAccel, 0.0f);
  uint32_t end = start + durationOf(timing);
  int phaseEdges = 0;
  for (uint32_t t = start; t < end; t += 211) {
    h.loopAt(t);
    RefState r = referenceSigma(timing, t - start);
    EXPECT_NEAR(gRate, 50.0 * r.nu, 1e-3 * 120 + 1e-4 * std::fabs(50.0 * r.nu)) << t;
    // At a phase change the two sides differ; only compare away from them.
    RefState before = referenceSigma(timing, t - start - 1.0);
    if (before.acc == r.acc)
      EXPECT_NEAR(gAccel, 50.0 * r.acc, 1e-3 * 1500) << t;
    else
      phaseEdges++;
  }
  EXPECT_LE(phaseEdges, 2);
  h.loopAt(end + 1);
  EXPECT_EQ(gRate, 0.0f);
  EXPECT_EQ(gAccel, 0.0f);
}

TEST(Evaluation, StatusOnStateChangesAndPeriodically) {
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  std::vector<int32_t> p0 = {0};
  msg::TimingSegment timing = trapezoid(50.0, 0, 100, 0, 1000);  // ~0.6 s
  uint32_t start = 100000;
  EXPECT_EQ(h.exchange(h.author.geometry(0, &p0, {{50.0f, {mm(50)}}}, 1)).reason, 0);
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {timing})).reason, 0);
  // Timing queued: the device reports running straight away.
  std::vector<msg::Status> statuses;
  uint32_t end = start + durationOf(timing);
  for (uint32_t t = 1000; t < end + 300000; t += 1000) {
    h.loopAt(t);
    for (auto& p : h.take()) {
      if (p.type != type::STATUS) continue;
      msg::Status s;
      ASSERT_TRUE(msg::parse(p.payload.data(), (uint8_t)p.payload.size(), s));
      statuses.push_back(s);
    }
  }
  ASSERT_GE(statuses.size(), 6u);
  EXPECT_EQ(statuses.front().state, state::RUNNING);
  EXPECT_EQ(statuses.back().state, state::IDLE);
  EXPECT_EQ(statuses.back().segmentId, 0);
  EXPECT_EQ(statuses.back().sigma, 1.0f);
  EXPECT_EQ(statuses.back().depth, 0);
  // While running: at least every 100 ms, and sigma rises.
  float lastSigma = -1;
  for (size_t i = 1; i + 1 < statuses.size(); i++) {
    EXPECT_LE(statuses[i].now - statuses[i - 1].now, 100000u);
    if (statuses[i].state == state::RUNNING && statuses[i].now >= start) {
      EXPECT_GE(statuses[i].sigma, lastSigma);
      lastSigma = statuses[i].sigma;
    }
  }
  // Idle: no more periodic statuses.
  h.take();
  for (uint32_t t = end + 300000; t < end + 800000; t += 10000) h.loopAt(t);
  EXPECT_TRUE(h.take().empty());
}
