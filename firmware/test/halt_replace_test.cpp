// HALT modes 0 and 1, and REPLACE_TAIL (protocol §4, §6).
#include <gtest/gtest.h>

#include <cmath>

#include "support/harness.h"

using namespace maxl_fw;
using namespace maxltest;

namespace {
void onPosition(float, float) {}
void onEvent(float) {}

// Four 10 mm segments at 100 mm/s from t = 100 000, one slot, timed.
void fourCruises(Harness& h) {
  std::vector<int32_t> p0 = {0};
  EXPECT_EQ(h.exchange(h.author.geometry(0, &p0, {{10.0f, {mm(10)}}, {10.0f, {mm(20)}}, {10.0f, {mm(30)}}, {10.0f, {mm(40)}}}, 1)).reason, 0);
  uint32_t start = 100000;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {cruise(100000), cruise(100000), cruise(100000), cruise(100000)})).reason, 0);
}
}  // namespace

TEST(Halt, ModeZeroStopsNowAndDropsEverything) {
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  fourCruises(h);
  h.loopAt(150000);
  int32_t here = h.device->positionUnits(0);
  EXPECT_NEAR(here, mm(5), 8);
  EXPECT_EQ(h.exchange(h.author.halt(HALT_NOW, 12345)).reason, 0);
  EXPECT_EQ(h.device->state(), state::HALTED);
  EXPECT_EQ(h.device->motion().queue().count(), 0);
  for (uint32_t t = 150000; t < 600000; t += 10000) {
    h.loopAt(t);
    EXPECT_EQ(h.device->positionUnits(0), here);
  }
  // The next GEOMETRY may continue from where it holds without a p0.
  EXPECT_EQ(h.exchange(h.author.geometry(4, nullptr, {{1.0f, {here + mm(1)}}}, 1)).reason, 0);
  EXPECT_EQ(h.device->motion().base(0), here);
}

TEST(Halt, ModeOneBrakesFromItsTime) {
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  fourCruises(h);
  h.loopAt(120000);
  // Brake from 250 000 (segment 1, σ = 0.5, 15 mm) at 1000 mm/s²: 5 mm in 0.1 s.
  EXPECT_EQ(h.exchange(h.author.halt(HALT_BRAKE_AT, 250000)).reason, 0);
  EXPECT_FALSE(h.device->statusFlags() & status_flag::LATE);
  for (uint32_t t = 120000; t < 250000; t += 1000) {
    h.loopAt(t);
    EXPECT_NEAR(h.device->positionUnits(0), mm((t - 100000) * 1e-4), 8) << t;
  }
  for (uint32_t t = 250000; t <= 400000; t += 1000) {
    h.loopAt(t);
    double tau = std::min(0.1, (t - 250000) * 1e-6);
    EXPECT_NEAR(h.device->positionUnits(0), mm(15 + 100 * tau - 500 * tau * tau), 40) << t;
  }
  EXPECT_EQ(h.device->positionUnits(0), mm(20));
  EXPECT_EQ(h.device->state(), state::STOPPED);
}

TEST(Halt, ModeOneTooLateBrakesAtOnceAndSaysLate) {
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  fourCruises(h);
  h.at(150000);
  EXPECT_EQ(h.exchange(h.author.halt(HALT_BRAKE_AT, 140000)).reason, 0);
  EXPECT_TRUE(h.device->statusFlags() & status_flag::LATE);
  EXPECT_EQ(h.device->state(), state::BRAKING);
  h.loopAt(400000);
  EXPECT_EQ(h.device->positionUnits(0), mm(10));  // 5 mm + 5 mm of braking
  EXPECT_EQ(h.device->state(), state::STOPPED);
}

TEST(Halt, UnknownModeIsMalformed) {
  Harness h;
  h.open({});
  EXPECT_EQ(h.exchange(h.author.halt(2, 0)).reason, nack::MALFORMED);
}

TEST(ReplaceTail, DropsSegmentsNotStarted) {
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  fourCruises(h);
  h.loopAt(150000);
  Answer a = h.exchange(h.author.replaceTail(2));
  EXPECT_EQ(a.reason, 0);
  EXPECT_EQ(h.device->motion().queue().count(), 2);
  EXPECT_EQ(h.device->motion().queue().timed(), 2);
  // The new tail continues from segment 1's end, with id 2.
  EXPECT_EQ(h.exchange(h.author.geometry(3, nullptr, {{5.0f, {mm(25)}}}, 1)).detail, 2);
  EXPECT_EQ(h.exchange(h.author.geometry(2, nullptr, {{5.0f, {mm(25)}}}, 1)).reason, 0);
  EXPECT_EQ(h.exchange(h.author.timing(2, 1000.0f, nullptr, {trapezoid(5, 100, 100, 0, 1000)})).reason, 0);
  h.loopAt(1000000);
  EXPECT_EQ(h.device->positionUnits(0), mm(25));
  EXPECT_EQ(h.device->state(), state::IDLE);
}

TEST(ReplaceTail, RefusesWhatStartedAndWhatIsUnknown) {
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  fourCruises(h);
  h.loopAt(250000);  // segment 0 done, 1 running
  Answer running = h.exchange(h.author.replaceTail(1));
  EXPECT_EQ(running.reason, nack::ALREADY_STARTED);
  EXPECT_EQ(running.detail, 1);
  EXPECT_EQ(h.exchange(h.author.replaceTail(0)).reason, nack::ALREADY_STARTED);  // run and gone
  Answer unknown = h.exchange(h.author.replaceTail(9));
  EXPECT_EQ(unknown.reason, nack::UNKNOWN_SEGMENT);
  EXPECT_EQ(unknown.detail, 9);
  EXPECT_EQ(h.exchange(h.author.replaceTail(4)).reason, 0);  // the next id: nothing to drop
  EXPECT_EQ(h.device->motion().queue().count(), 3);
}

TEST(ReplaceTail, DropsTheirEvents) {
  MAXL_TrackEvent e("e", onEvent);
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  h.open({{0, kind::EVENT, 0}, {1, kind::POSITION, 0}});
  fourCruises(h);
  EXPECT_EQ(h.exchange(h.author.events(1, 0, 0, {{10, 1.0f}})).reason, 0);
  EXPECT_EQ(h.exchange(h.author.events(3, 0, 0, {{10, 2.0f}, {20, 3.0f}})).reason, 0);
  Answer a = h.exchange(h.author.replaceTail(2));
  EXPECT_EQ(a.freeEvents, MAXL_EVENT_CAPACITY - 1);
  // Segment 2 again, with new events starting at index 0.
  EXPECT_EQ(h.exchange(h.author.geometry(2, nullptr, {{10.0f, {mm(30)}}}, 1)).reason, 0);
  EXPECT_EQ(h.exchange(h.author.timing(2, 1000.0f, nullptr, {cruise(100000)})).reason, 0);
  EXPECT_EQ(h.exchange(h.author.events(2, 0, 0, {{0, 5.0f}})).reason, 0);
}
