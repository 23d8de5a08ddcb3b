// Dwells on the device (protocol §4 GEOMETRY/TIMING, §5, §6): a segment of
// length 0 holds its position for its duration; one of 0 µs is an instant
// whose events happen at its start. Readers see it like any segment.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "support/harness.h"
#include "support/reference.h"

using namespace maxl_fw;
using namespace maxltest;

namespace {

struct Seen {
  uint32_t t;
  float v;
};
uint32_t gNow = 0;
std::vector<Seen> gPen;
std::vector<Seen> gPositions;
float gRate = -1.0f;
float gAccel = -1.0f;
void onPen(float v) { gPen.push_back({gNow, v}); }
void onPosition(float p, float) { gPositions.push_back({gNow, p}); }
void onRate(float v) { gRate = v; }
void onAccel(float a) { gAccel = a; }

// A dwell's timing: one phase at σ'' = 0 lasting `us` (the author sends alpha 0).
msg::TimingSegment dwell(uint32_t us) {
  msg::TimingSegment t{};
  t.shape = phase::CRUISE;
  t.phaseCount = 1;
  t.durations[0] = us;
  t.alpha = 0.0f;
  return t;
}

void runTo(Harness& h, uint32_t from, uint32_t to, uint32_t step = 1) {
  for (uint32_t t = from; t <= to; t += step) {
    gNow = t;
    h.loopAt(t);
  }
}

// Pen down over a dwell: 10 mm to rest, a 120 ms dwell that sets pen = 1 at
// its start and 0.5 half-way, then 10 mm on. Times of the three segments.
struct PenJob {
  msg::TimingSegment a = trapezoid(10.0, 0, 100, 0, 1000);  // 200 ms
  msg::TimingSegment d = dwell(120000);
  msg::TimingSegment b = trapezoid(10.0, 0, 100, 0, 1000);
  uint32_t start = 100000;
  uint32_t dwellStart() const { return start + durationOf(a); }
  uint32_t dwellEnd() const { return dwellStart() + 120000; }
  uint32_t end() const { return dwellEnd() + durationOf(b); }
};

void sendPenJob(Harness& h, const PenJob& job) {
  std::vector<int32_t> p0 = {0};
  ASSERT_EQ(h.exchange(h.author.geometry(0, &p0, {{10.0f, {mm(10)}}, {0.0f, {mm(10)}}, {10.0f, {mm(20)}}}, 1)).reason, 0);
  uint32_t start = job.start;
  ASSERT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {job.a, job.d, job.b})).reason, 0);
  ASSERT_EQ(h.exchange(h.author.events(1, 0, 0, {{0, 1.0f}, {60000, 0.5f}})).reason, 0);
}
}  // namespace

TEST(Dwell, HoldsPositionFiresEventsAtTheirTimeAtZeroSpeed) {
  MAXL_TrackPositionLinear x("x", onPosition);
  MAXL_TrackEvent pen("pen", onPen);
  MAXL_TrackVelocity v("v", onRate);
  MAXL_TrackAcceleration acc("acc", onAccel);
  Harness h;
  h.open({{0, kind::POSITION, 0}, {1, kind::EVENT, 0}, {2, kind::VELOCITY, 0}, {3, kind::ACCELERATION, 0}});
  PenJob job;
  sendPenJob(h, job);
  gPen.clear();
  gPositions.clear();
  float lastSigma = -1.0f;
  for (uint32_t t = job.start; t <= job.end() + 1000; t += 50) {
    gNow = t;
    h.loopAt(t);
    bool inDwell = t >= job.dwellStart() && t < job.dwellEnd();
    if (!inDwell) continue;
    // Position held exactly at the dwell's point; velocity and acceleration 0.
    EXPECT_EQ(h.device->positionUnits(0), mm(10)) << t;
    EXPECT_EQ(gRate, 0.0f) << t;
    EXPECT_EQ(gAccel, 0.0f) << t;
    EXPECT_EQ(h.device->state(), state::RUNNING) << t;
    // STATUS: the dwell's id, σ rising with time through it.
    if ((t - job.dwellStart()) % 10000 == 0) {
      h.take();
      h.send(h.author.statusRequest());
      msg::Status s = h.lastStatus();
      EXPECT_EQ(s.segmentId, 1) << t;
      EXPECT_NEAR(s.sigma, (t - job.dwellStart()) / 120000.0, 1e-4) << t;
      EXPECT_GE(s.sigma, lastSigma);
      lastSigma = s.sigma;
    }
  }
  // No position callback inside the dwell: nothing moved.
  for (const Seen& p : gPositions) EXPECT_FALSE(p.t > job.dwellStart() && p.t < job.dwellEnd()) << p.t;
  // The pen's changes at their exact times.
  ASSERT_EQ(gPen.size(), 2u);
  EXPECT_EQ(gPen[0].t, job.dwellStart());
  EXPECT_EQ(gPen[0].v, 1.0f);
  EXPECT_EQ(gPen[1].t, job.dwellStart() + 60000);
  EXPECT_EQ(gPen[1].v, 0.5f);
  // The next segment started from rest at the dwell's end and arrived.
  EXPECT_EQ(h.device->positionUnits(0), mm(20));
  EXPECT_EQ(h.device->state(), state::IDLE);
  EXPECT_FALSE(h.device->statusFlags() & status_flag::STARVED);
}

TEST(Dwell, AnInstantFiresItsEventsBetweenTheSegmentsAroundIt) {
  MAXL_TrackPositionLinear x("x", onPosition);
  MAXL_TrackEvent pen("pen", onPen);
  Harness h;
  h.open({{0, kind::POSITION, 0}, {1, kind::EVENT, 0}});
  std::vector<int32_t> p0 = {0};
  msg::TimingSegment a = trapezoid(10.0, 0, 100, 0, 1000);
  ASSERT_EQ(h.exchange(h.author.geometry(0, &p0, {{10.0f, {mm(10)}}, {0.0f, {mm(10)}}, {10.0f, {mm(0)}}}, 1)).reason, 0);
  uint32_t start = 50000;
  // T = 0 is refused for a segment that moves (segment 2), whole.
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {a, dwell(0), dwell(0)})).reason, nack::MALFORMED);
  EXPECT_EQ(h.device->motion().queue().timed(), 0);
  ASSERT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {a, dwell(0), a})).reason, 0);
  const uint32_t instant = start + durationOf(a);
  EXPECT_EQ(h.device->motion().queue().at(1).start, instant);
  EXPECT_EQ(h.device->motion().queue().at(2).start, instant);
  // Offsets past an instant's T = 0 are refused; 0 is its start.
  EXPECT_EQ(h.exchange(h.author.events(1, 0, 0, {{1, 1.0f}})).reason, nack::MALFORMED);
  ASSERT_EQ(h.exchange(h.author.events(1, 0, 0, {{0, 1.0f}})).reason, 0);
  gPen.clear();
  runTo(h, start, instant + durationOf(a) + 100);
  ASSERT_EQ(gPen.size(), 1u);
  EXPECT_EQ(gPen[0].t, instant);
  EXPECT_EQ(h.device->positionUnits(0), mm(0));
  EXPECT_EQ(h.device->state(), state::IDLE);
  EXPECT_FALSE(h.device->statusFlags() & status_flag::STARVED);
}

// Timing runs out before a dwell's timing came: the device brakes along the
// provisional geometry at stopDecel, through the dwell's point (it has no
// length to brake along) and on along the next segment, to the same point
// as without the dwell. Its events never came, so none fire.
TEST(Dwell, BrakingGoesThroughAProvisionalDwell) {
  for (bool withDwell : {false, true}) {
    MAXL_TrackPositionLinear x("x", onPosition);
    Harness h;
    h.open({{0, kind::POSITION, 0}});
    std::vector<int32_t> p0 = {0};
    std::vector<GeometrySegment> g = {{10.0f, {mm(10)}}, {2.0f, {mm(12)}}};
    if (withDwell) g.push_back({0.0f, {mm(12)}});
    g.push_back({10.0f, {mm(22)}});
    ASSERT_EQ(h.exchange(h.author.geometry(0, &p0, g, 1)).reason, 0);
    uint32_t start = 100000;
    msg::TimingSegment cruise = dwell(100000);  // 10 mm at 100 mm/s (alpha 0, one cruise phase)
    ASSERT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {cruise})).reason, 0);
    // 100 mm/s at 200 000, braking at 1000 mm/s²: 5 mm, 0.1 s, to 15 mm.
    for (uint32_t t = 100000; t <= 400000; t += 250) {
      h.loopAt(t);
      double tau = (t - 200000) * 1e-6;
      double s = t < 200000 ? (t - 100000) * 1e-4 : tau < 0.1 ? 10 + 100 * tau - 500 * tau * tau : 15.0;
      ASSERT_NEAR(h.device->positionUnits(0), mm(s), 40) << withDwell << " " << t;
    }
    EXPECT_EQ(h.device->positionUnits(0), mm(15));
    EXPECT_EQ(h.device->state(), state::STOPPED);
    h.take();
    h.send(h.author.statusRequest());
    msg::Status s = h.lastStatus();
    EXPECT_EQ(s.segmentId, withDwell ? 3 : 2);
    EXPECT_NEAR(s.sigma, 0.3, 1e-5);
  }
}

// HALT mode 1 inside a dwell: the machine is at rest there, so it stops at
// once where it holds; the dwell's later events go with its timing.
TEST(Dwell, HaltBrakeAtInsideADwellStopsWhereItHolds) {
  MAXL_TrackPositionLinear x("x", onPosition);
  MAXL_TrackEvent pen("pen", onPen);
  Harness h;
  h.open({{0, kind::POSITION, 0}, {1, kind::EVENT, 0}});
  PenJob job;
  sendPenJob(h, job);
  gPen.clear();
  runTo(h, job.start, job.dwellStart() + 10000, 100);
  const uint32_t at = job.dwellStart() + 30000;
  EXPECT_EQ(h.exchange(h.author.halt(HALT_BRAKE_AT, at)).reason, 0);
  runTo(h, job.dwellStart() + 10000, job.end() + 10000, 100);
  EXPECT_EQ(h.device->positionUnits(0), mm(10));
  EXPECT_EQ(h.device->state(), state::STOPPED);
  ASSERT_EQ(gPen.size(), 1u);  // the 0.5 at +60 ms came after the brake start
  EXPECT_EQ(gPen[0].v, 1.0f);
  h.take();
  h.send(h.author.statusRequest());
  msg::Status s = h.lastStatus();
  EXPECT_EQ(s.segmentId, 1);
  EXPECT_NEAR(s.sigma, 0.25, 1e-4);
  EXPECT_FALSE(s.flags & status_flag::LATE);
}

// A dwell is replaced like any provisional segment, and refused once it runs.
TEST(Dwell, ReplaceTailFromADwell) {
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  std::vector<int32_t> p0 = {0};
  ASSERT_EQ(h.exchange(h.author.geometry(0, &p0, {{10.0f, {mm(10)}}, {0.0f, {mm(10)}}, {5.0f, {mm(15)}}}, 1)).reason, 0);
  uint32_t start = 100000;
  msg::TimingSegment a = trapezoid(10.0, 0, 100, 0, 1000);
  ASSERT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {a})).reason, 0);
  EXPECT_EQ(h.exchange(h.author.replaceTail(1)).reason, 0);
  EXPECT_EQ(h.device->motion().queue().count(), 1);
  ASSERT_EQ(h.exchange(h.author.geometry(1, nullptr, {{0.0f, {mm(10)}}}, 1)).reason, 0);
  ASSERT_EQ(h.exchange(h.author.timing(1, 1000.0f, nullptr, {dwell(50000)})).reason, 0);
  runTo(h, start, start + durationOf(a) + 20000, 500);
  EXPECT_EQ(h.exchange(h.author.replaceTail(1)).reason, nack::ALREADY_STARTED);
  runTo(h, start + durationOf(a) + 20500, start + durationOf(a) + 60000, 500);
  EXPECT_EQ(h.device->state(), state::IDLE);
  EXPECT_EQ(h.device->positionUnits(0), mm(10));
}
