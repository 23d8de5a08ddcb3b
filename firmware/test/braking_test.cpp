// Always stoppable (protocol §6): when timing runs out while moving, the
// device brakes along the provisional geometry at stopDecel and holds.
#include <gtest/gtest.h>

#include <cmath>

#include "support/harness.h"
#include "support/reference.h"

using namespace maxl_fw;
using namespace maxltest;

namespace {
void onPosition(float, float) {}

}  // namespace

TEST(Braking, StarvedReaderBrakesAlongProvisionalGeometryAndHolds) {
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  // 10 mm at 100 mm/s (timed), then 3 provisional segments of 2 mm.
  std::vector<int32_t> p0 = {mm(0)};
  EXPECT_EQ(h.exchange(h.author.geometry(0, &p0, {{10.0f, {mm(10)}}, {2.0f, {mm(12)}}, {2.0f, {mm(14)}}, {2.0f, {mm(16)}}}, 1)).reason, 0);
  uint32_t start = 100000;
  const float decel = 1000.0f;
  EXPECT_EQ(h.exchange(h.author.timing(0, decel, &start, {cruise(100000)})).reason, 0);
  // Runs the timed segment normally.
  h.loopAt(150000);
  EXPECT_NEAR(h.device->positionUnits(0), mm(5), 8);
  EXPECT_EQ(h.device->state(), state::RUNNING);
  // v = 100 mm/s at 200 000: braking distance v²/2D = 5 mm, over 0.1 s:
  // leaves segment 1 (2 mm) at √(100² − 2·1000·2) = 77.46 mm/s, segment 2 at
  // √(77.46² − 4000) = 44.72 mm/s, stops inside segment 3 after 1 mm more.
  h.take();
  double lastPos = mm(10);
  for (uint32_t t = 200000; t <= 320000; t += 500) {
    h.loopAt(t);
    double tau = (t - 200000) * 1e-6;
    double s = tau < 0.1 ? 100 * tau - 0.5 * decel * tau * tau : 5.0;
    EXPECT_NEAR(h.device->positionUnits(0), mm(10 + s), 40) << t;
    EXPECT_GE(h.device->positionUnits(0), lastPos - 2);  // never backwards
    lastPos = h.device->positionUnits(0);
  }
  EXPECT_EQ(h.device->positionUnits(0), mm(15));
  EXPECT_EQ(h.device->state(), state::STOPPED);
  EXPECT_TRUE(h.device->statusFlags() & status_flag::STARVED);
  // The STATUS names the segment and σ where it stopped: id 3, σ = 1/2.
  h.send(h.author.statusRequest());
  msg::Status s = h.lastStatus();
  EXPECT_EQ(s.state, state::STOPPED);
  EXPECT_EQ(s.segmentId, 3);
  EXPECT_NEAR(s.sigma, 0.5, 1e-5);
  EXPECT_EQ(s.depth, 1);  // segment 3 is still queued, started
  EXPECT_TRUE(s.flags & status_flag::STARVED);
  // It holds there.
  for (uint32_t t = 400000; t < 1000000; t += 50000) {
    h.loopAt(t);
    EXPECT_EQ(h.device->positionUnits(0), mm(15));
  }
  // Segment 3 is started: it can be neither timed nor replaced.
  EXPECT_EQ(h.exchange(h.author.timing(3, decel, nullptr, {cruise(1000)})).reason, nack::LATE_SEGMENT);
  EXPECT_EQ(h.exchange(h.author.replaceTail(3)).reason, nack::ALREADY_STARTED);
  // HALT 0 then new geometry from the stop point resumes.
  EXPECT_EQ(h.exchange(h.author.halt(HALT_NOW, 0)).reason, 0);
  EXPECT_EQ(h.device->motion().queue().count(), 0);
  std::vector<int32_t> here = {mm(15)};
  EXPECT_EQ(h.exchange(h.author.geometry(100, &here, {{1.0f, {mm(16)}}}, 1)).reason, 0);
  uint32_t again = 1100000;
  EXPECT_EQ(h.exchange(h.author.timing(100, decel, &again, {trapezoid(1.0, 0, 50, 0, 1000)})).reason, 0);
  h.loopAt(1500000);
  EXPECT_EQ(h.device->positionUnits(0), mm(16));
  EXPECT_EQ(h.device->state(), state::IDLE);
}

TEST(Braking, WithoutProvisionalGeometryItStopsAtTheEnd) {
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  std::vector<int32_t> p0 = {mm(0)};
  EXPECT_EQ(h.exchange(h.author.geometry(0, &p0, {{10.0f, {mm(10)}}}, 1)).reason, 0);
  uint32_t start = 1000;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {cruise(100000)})).reason, 0);
  h.loopAt(200000);
  EXPECT_EQ(h.device->positionUnits(0), mm(10));
  EXPECT_EQ(h.device->state(), state::STOPPED);
  EXPECT_TRUE(h.device->statusFlags() & status_flag::STARVED);
}

TEST(Braking, EndingAtRestIsIdleNotStarved) {
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  std::vector<int32_t> p0 = {mm(0)};
  EXPECT_EQ(h.exchange(h.author.geometry(0, &p0, {{10.0f, {mm(10)}}, {5.0f, {mm(15)}}}, 1)).reason, 0);
  uint32_t start = 1000;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {trapezoid(10, 0, 100, 0, 1000)})).reason, 0);
  h.loopAt(2000000);
  EXPECT_EQ(h.device->positionUnits(0), mm(10));
  EXPECT_EQ(h.device->state(), state::IDLE);
  EXPECT_FALSE(h.device->statusFlags() & status_flag::STARVED);
  EXPECT_EQ(h.device->motion().queue().count(), 1);  // the provisional segment waits
}

TEST(Braking, TimingInTimeAvoidsBraking) {
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  std::vector<int32_t> p0 = {mm(0)};
  EXPECT_EQ(h.exchange(h.author.geometry(0, &p0, {{10.0f, {mm(10)}}, {10.0f, {mm(20)}}}, 1)).reason, 0);
  uint32_t start = 1000;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {cruise(100000)})).reason, 0);
  h.at(90000);
  EXPECT_EQ(h.exchange(h.author.timing(1, 1000.0f, nullptr, {cruise(100000)})).reason, 0);
  for (uint32_t t = 90000; t < 201000; t += 1000) {
    h.loopAt(t);
    double expected = std::min(20.0, std::max(0.0, (t - 1000) * 1e-4));
    EXPECT_NEAR(h.device->positionUnits(0), mm(expected), 8) << t;
  }
  EXPECT_FALSE(h.device->statusFlags() & status_flag::STARVED);
  // Without more timing, the end of segment 1 (at speed, nothing after) starves.
  h.loopAt(202000);
  EXPECT_TRUE(h.device->statusFlags() & status_flag::STARVED);
  EXPECT_EQ(h.device->state(), state::STOPPED);
}
