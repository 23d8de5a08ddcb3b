// SUBSCRIBE, GEOMETRY and TIMING acceptance rules (protocol §4).
#include <gtest/gtest.h>

#include <cmath>

#include "support/harness.h"

using namespace maxl_fw;
using namespace maxltest;

namespace {
void position(float, float) {}
void rate(float) {}
const std::vector<int32_t> ORIGIN1 = {0};

}  // namespace

TEST(Subscribe, Rules) {
  MAXL_TrackPositionLinear x("x", position);
  MAXL_TrackVelocity v("v", rate);
  Harness h;
  h.open({});
  EXPECT_EQ(h.exchange(h.author.subscribe(2, kind::POSITION, 0)).reason, nack::BAD_SUBSCRIPTION);  // no reader 2
  Answer wrongKind = h.exchange(h.author.subscribe(1, kind::POSITION, 0));
  EXPECT_EQ(wrongKind.reason, nack::BAD_SUBSCRIPTION);
  EXPECT_EQ(wrongKind.detail, 1);
  EXPECT_EQ(h.exchange(h.author.subscribe(1, kind::VELOCITY, 1)).reason, nack::BAD_SUBSCRIPTION);  // slot must be 0
  EXPECT_EQ(h.exchange(h.author.subscribe(0, kind::POSITION, MAXL_POSITION_SLOTS)).reason, nack::BAD_SUBSCRIPTION);
  EXPECT_EQ(h.exchange(h.author.subscribe(0, kind::POSITION, 1)).reason, 0);
  EXPECT_EQ(h.device->motion().activeSlots(), 2);  // P = highest slot + 1
  EXPECT_EQ(h.exchange(h.author.subscribe(0, kind::POSITION, 0)).reason, 0);
  EXPECT_EQ(h.device->motion().activeSlots(), 1);
  // Not while segments are queued.
  EXPECT_EQ(h.exchange(h.author.geometry(0, &ORIGIN1, {{1.0f, {65536}}}, 1)).reason, 0);
  EXPECT_EQ(h.exchange(h.author.subscribe(1, kind::VELOCITY, 0)).reason, nack::BAD_SUBSCRIPTION);
}

TEST(Geometry, IdsAndP0) {
  MAXL_TrackPositionLinear x("x", position);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  // The first GEOMETRY of a session needs p0.
  Answer a = h.exchange(h.author.geometry(0, nullptr, {{1.0f, {65536}}}, 1));
  EXPECT_EQ(a.reason, nack::MALFORMED);
  // With p0, any first id.
  a = h.exchange(h.author.geometry(40000, &ORIGIN1, {{1.0f, {65536}}, {1.0f, {131072}}}, 1));
  EXPECT_EQ(a.reason, 0);
  EXPECT_EQ(a.freeSegments, MAXL_SEGMENT_CAPACITY - 2);
  // Then ids must follow.
  a = h.exchange(h.author.geometry(40003, nullptr, {{1.0f, {0}}}, 1));
  EXPECT_EQ(a.reason, nack::MALFORMED);
  EXPECT_EQ(a.detail, 40002);
  EXPECT_EQ(h.exchange(h.author.geometry(40002, nullptr, {{1.0f, {0}}}, 1)).reason, 0);
  // Lengths must be >= 0 and finite; the count at least one. A length of 0 is
  // a dwell: it must hold where it starts (segment 40002 ends at 0).
  EXPECT_EQ(h.exchange(h.author.geometry(40003, nullptr, {{0.0f, {1}}}, 1)).reason, nack::MALFORMED);
  EXPECT_EQ(h.exchange(h.author.geometry(40003, nullptr, {{1.0f, {65536}}, {0.0f, {0}}}, 1)).reason, nack::MALFORMED);
  EXPECT_EQ(h.exchange(h.author.geometry(40003, nullptr, {{-1.0f, {0}}}, 1)).reason, nack::MALFORMED);
  EXPECT_EQ(h.device->motion().queue().count(), 3);  // nothing of those was added
  EXPECT_EQ(h.exchange(h.author.geometry(40003, nullptr, {{INFINITY, {0}}}, 1)).reason, nack::MALFORMED);
  EXPECT_EQ(h.exchange(h.author.geometry(40003, nullptr, {}, 1)).reason, nack::MALFORMED);
  // The payload's size follows P (one slot subscribed): two values per segment is malformed.
  EXPECT_EQ(h.exchange(h.author.geometry(40003, nullptr, {{1.0f, {0, 0}}}, 2)).reason, nack::MALFORMED);
  // Dwells that hold: after 40002 (ends at 0), and after a segment of the same frame.
  EXPECT_EQ(h.exchange(h.author.geometry(40003, nullptr, {{0.0f, {0}}, {2.0f, {131072}}, {0.0f, {131072}}}, 1)).reason, 0);
  EXPECT_EQ(h.device->motion().queue().count(), 6);
}

TEST(Geometry, QueueFullAddsNothingAndSetsTheFlag) {
  MAXL_TrackPositionLinear x("x", position);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  uint16_t id = 0;
  EXPECT_EQ(h.exchange(h.author.geometry(id++, &ORIGIN1, {{1.0f, {0}}}, 1)).reason, 0);
  while (id < MAXL_SEGMENT_CAPACITY - 1) EXPECT_EQ(h.exchange(h.author.geometry(id++, nullptr, {{1.0f, {0}}}, 1)).reason, 0);
  Answer full = h.exchange(h.author.geometry(id, nullptr, {{1.0f, {0}}, {1.0f, {0}}}, 1));
  EXPECT_EQ(full.reason, nack::QUEUE_FULL);
  EXPECT_EQ(full.detail, 1);
  EXPECT_EQ(h.device->motion().queue().count(), MAXL_SEGMENT_CAPACITY - 1);
  EXPECT_TRUE(h.device->statusFlags() & status_flag::QUEUE_FULL);
  EXPECT_EQ(h.exchange(h.author.geometry(id, nullptr, {{1.0f, {0}}}, 1)).reason, 0);
  EXPECT_EQ(h.device->motion().queue().free(), 0);
}

TEST(Timing, MustGoToTheFirstUntimedQueuedSegments) {
  MAXL_TrackPositionLinear x("x", position);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  EXPECT_EQ(h.exchange(h.author.geometry(5, &ORIGIN1, {{1.0f, {65536}}, {1.0f, {131072}}}, 1)).reason, 0);
  uint32_t start = 10000;
  Answer a = h.exchange(h.author.timing(6, 1000.0f, &start, {cruise(1000)}));
  EXPECT_EQ(a.reason, nack::UNKNOWN_SEGMENT);
  EXPECT_EQ(a.detail, 6);
  a = h.exchange(h.author.timing(5, 1000.0f, &start, {cruise(1000), cruise(1000), cruise(1000)}));
  EXPECT_EQ(a.reason, nack::UNKNOWN_SEGMENT);
  EXPECT_EQ(a.detail, 7);  // the first id without geometry
  EXPECT_EQ(h.exchange(h.author.timing(5, 1000.0f, &start, {cruise(1000)})).reason, 0);
  EXPECT_EQ(h.device->motion().queue().timed(), 1);
  // Contiguous: no start needed now.
  EXPECT_EQ(h.exchange(h.author.timing(6, 1000.0f, nullptr, {cruise(1000)})).reason, 0);
  EXPECT_EQ(h.device->motion().queue().at(1).start, 11000u);
}

TEST(Timing, MalformedProfilesAreRefusedWhole) {
  MAXL_TrackPositionLinear x("x", position);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  EXPECT_EQ(h.exchange(h.author.geometry(0, &ORIGIN1, {{1.0f, {65536}}, {1.0f, {131072}}}, 1)).reason, 0);
  uint32_t start = 10000;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, nullptr, {cruise(1000)})).reason, nack::MALFORMED);  // no history
  EXPECT_EQ(h.exchange(h.author.timing(0, 0.0f, &start, {cruise(1000)})).reason, nack::MALFORMED);      // stopDecel
  EXPECT_EQ(h.exchange(h.author.timing(0, NAN, &start, {cruise(1000)})).reason, nack::MALFORMED);
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {cruise(0)})).reason, nack::MALFORMED);       // T = 0
  msg::TimingSegment none{};
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {none})).reason, nack::MALFORMED);           // no phase
  msg::TimingSegment gap = cruise(1000);
  gap.shape = 0x08;  // cruise after NONE
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {gap})).reason, nack::MALFORMED);
  msg::TimingSegment negative = cruise(1000);
  negative.alpha = -5.0f;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {negative})).reason, nack::MALFORMED);
  // A good first segment and a bad second one: nothing is applied.
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {cruise(1000), cruise(0)})).reason, nack::MALFORMED);
  EXPECT_EQ(h.device->motion().queue().timed(), 0);
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {cruise(1000), cruise(1000)})).reason, 0);
  EXPECT_EQ(h.device->motion().queue().timed(), 2);
}

TEST(Timing, TooFastForFixedPointIsMalformed) {
  MAXL_TrackPositionLinear x("x", position);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  // 30 m in 10 µs.
  EXPECT_EQ(h.exchange(h.author.geometry(0, &ORIGIN1, {{30000.0f, {30000 * 65536}}}, 1)).reason, 0);
  uint32_t start = 10000;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {cruise(10)})).reason, nack::MALFORMED);
}

TEST(Timing, LateSegmentIsRefusedAndNeverRun) {
  MAXL_TrackPositionLinear x("x", position);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  h.at(50000);
  EXPECT_EQ(h.exchange(h.author.geometry(0, &ORIGIN1, {{1.0f, {65536}}, {1.0f, {131072}}}, 1)).reason, 0);
  uint32_t start = 49999;  // 1 µs in the past
  Answer a = h.exchange(h.author.timing(0, 1000.0f, &start, {cruise(1000), cruise(1000)}));
  EXPECT_EQ(a.reason, nack::LATE_SEGMENT);
  EXPECT_EQ(a.detail, 0);
  EXPECT_EQ(h.device->motion().queue().timed(), 0);
  EXPECT_TRUE(h.device->statusFlags() & status_flag::LATE);
  for (uint32_t t = 50000; t < 60000; t += 100) {
    h.loopAt(t);
    EXPECT_EQ(h.device->positionUnits(0), 0);  // never moves
  }
  EXPECT_EQ(h.device->state(), state::IDLE);
}

TEST(Timing, ASegmentBeingBrakedAlongIsLate) {
  MAXL_TrackPositionLinear x("x", position);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  h.at(50000);
  EXPECT_EQ(h.exchange(h.author.geometry(0, &ORIGIN1, {{1.0f, {65536}}, {1.0f, {131072}}, {1.0f, {196608}}}, 1)).reason, 0);
  uint32_t start = 60000;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {cruise(1000)})).reason, 0);
  // Segment 1 contiguous with 0 (starts at 61000), segment 2 would start at
  // 62000; the device is already at 61500.
  h.at(61500);
  Answer a = h.exchange(h.author.timing(1, 1000.0f, nullptr, {cruise(1000), cruise(1000)}));
  EXPECT_EQ(a.reason, nack::LATE_SEGMENT);
  EXPECT_EQ(a.detail, 1);  // segment 1 started at 61000 < 61500: late, and so is 2
  EXPECT_EQ(h.device->motion().queue().timed(), 0);  // 0 has run and retired
}

TEST(Timing, KeepsEarlierSegmentsOfTheBatch) {
  MAXL_TrackPositionLinear x("x", position);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  h.at(50000);
  EXPECT_EQ(h.exchange(h.author.geometry(0, &ORIGIN1, {{1.0f, {65536}}, {1.0f, {131072}}}, 1)).reason, 0);
  uint32_t start = 60000;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {cruise(1000), cruise(1000)})).reason, 0);
  EXPECT_EQ(h.device->motion().queue().timed(), 2);
}

TEST(Status, ReportsStateDepthAndSticksFlags) {
  MAXL_TrackPositionLinear x("x", position);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  EXPECT_EQ(h.exchange(h.author.geometry(0, &ORIGIN1, {{1.0f, {65536}}, {1.0f, {131072}}}, 1)).reason, 0);
  h.take();
  h.send(h.author.statusRequest());
  std::vector<Packet> p = h.take();
  ASSERT_EQ(p.size(), 2u);
  ASSERT_EQ(p[0].type, type::STATUS);  // the reply, then the ACK
  msg::Status s;
  ASSERT_TRUE(msg::parse(p[0].payload.data(), (uint8_t)p[0].payload.size(), s));
  EXPECT_EQ(s.state, state::IDLE);
  EXPECT_EQ(s.depth, 2);
  EXPECT_EQ(s.flags, 0);
  EXPECT_EQ(p[1].type, type::ACK);
}

// A TIMING without start continues the timing before it. Once that timing has
// run out (the segments ran and retired, or the device braked to rest along its
// geometry for lack of timing), the start is in the past: LATE_SEGMENT, as for
// any late start, not MALFORMED. Only with no timing at all in the session (or
// since a HALT mode 0) is there nothing to continue.
namespace {

msg::Status statusNow(Harness& h) {
  h.take();
  h.send(h.author.statusRequest());
  return h.lastStatus();
}

// The refused continuation changed nothing: segment `id` is the first without
// timing, the device holds at `here`, reports late, and a TIMING with a start
// ahead is accepted and runs to `to`.
void lateThenRestart(Harness& h, uint16_t id, int32_t here, int32_t to, uint8_t restState) {
  Answer a = h.exchange(h.author.timing(id, 1000.0f, nullptr, {trapezoid(10, 0, 100, 0, 1000)}));
  EXPECT_EQ(a.reason, nack::LATE_SEGMENT);
  EXPECT_EQ(a.detail, id);
  EXPECT_EQ(h.device->motion().queue().timed(), 0);
  EXPECT_EQ(h.device->motion().queue().headId(), id);
  EXPECT_TRUE(h.device->statusFlags() & status_flag::LATE);
  msg::Status s = statusNow(h);
  EXPECT_EQ(s.state, restState);
  EXPECT_TRUE(s.flags & status_flag::LATE);
  for (int k = 0; k < 5; k++) {
    h.loopAt(h.now() + 20000);
    EXPECT_EQ(h.device->positionUnits(0), here);  // nothing was applied
  }
  uint32_t start = h.now() + 50000;
  EXPECT_EQ(h.exchange(h.author.timing(id, 1000.0f, &start, {trapezoid(10, 0, 100, 0, 1000)})).reason, 0);
  EXPECT_EQ(h.device->motion().queue().timed(), 1);
  EXPECT_EQ(h.device->state(), state::RUNNING);
  h.loopAt(start + 100000);
  EXPECT_NEAR(h.device->positionUnits(0), here + (to - here) / 2, 16);
  h.loopAt(start + 400000);
  EXPECT_EQ(h.device->positionUnits(0), to);
}
}  // namespace

TEST(Timing, ContinuationAfterTheTimedSegmentsRetiredIsLate) {
  MAXL_TrackPositionLinear x("x", position);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  h.at(50000);
  // Two timed segments ending at rest, then provisional geometry.
  EXPECT_EQ(h.exchange(h.author.geometry(0, &ORIGIN1, {{10.0f, {mm(10)}}, {10.0f, {mm(20)}}, {10.0f, {mm(30)}}, {10.0f, {mm(40)}}}, 1)).reason, 0);
  uint32_t start = 100000;
  msg::TimingSegment rest = trapezoid(10, 0, 100, 0, 1000);
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {rest})).reason, 0);
  EXPECT_EQ(h.exchange(h.author.timing(1, 1000.0f, nullptr, {rest})).reason, 0);
  for (uint32_t t = 100000; t <= 600000; t += 1000) h.loopAt(t);
  EXPECT_EQ(h.device->positionUnits(0), mm(20));
  EXPECT_EQ(h.device->state(), state::IDLE);
  EXPECT_EQ(h.device->motion().queue().count(), 2);  // 2 and 3, provisional
  EXPECT_EQ(h.device->statusFlags(), 0);
  // The continuation of segment 1 (ended at 500 000) arrives late.
  lateThenRestart(h, 2, mm(20), mm(30), state::IDLE);
  // And again after 40 minutes at rest (past the half-wrap of the µs clock: the
  // end of the last timing must not come to look like the future).
  h.loopAt(h.now() + 2400000000u);
  EXPECT_EQ(h.device->state(), state::IDLE);
  lateThenRestart(h, 3, mm(30), mm(40), state::IDLE);
}

TEST(Timing, ContinuationAfterBrakingToRestIsLate) {
  MAXL_TrackPositionLinear x("x", position);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  // 10 mm at 100 mm/s, then 2 mm of provisional geometry: starved at 200 000, the
  // device brakes (5 mm needed at 1000 mm/s²) and stops at the end of the geometry.
  EXPECT_EQ(h.exchange(h.author.geometry(0, &ORIGIN1, {{10.0f, {mm(10)}}, {2.0f, {mm(12)}}}, 1)).reason, 0);
  uint32_t start = 100000;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {cruise(100000)})).reason, 0);
  for (uint32_t t = 100000; t <= 400000; t += 1000) h.loopAt(t);
  EXPECT_EQ(h.device->state(), state::STOPPED);
  EXPECT_EQ(h.device->positionUnits(0), mm(12));
  EXPECT_EQ(h.device->motion().queue().count(), 0);
  // The queue emptied: geometry for the next segment continues the ids, and its
  // timing, contiguous with segment 0's, is late.
  EXPECT_EQ(h.exchange(h.author.geometry(2, nullptr, {{10.0f, {mm(22)}}}, 1)).reason, 0);
  lateThenRestart(h, 2, mm(12), mm(22), state::STOPPED);
  EXPECT_TRUE(h.device->statusFlags() & status_flag::STARVED);
}

TEST(Timing, ContinuationAfterAHaltBrakeIsLate) {
  MAXL_TrackPositionLinear x("x", position);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  // The session's first segment brakes from a HALT mode 1 and never reaches its end.
  EXPECT_EQ(h.exchange(h.author.geometry(0, &ORIGIN1, {{10.0f, {mm(10)}}}, 1)).reason, 0);
  uint32_t start = 100000;
  EXPECT_EQ(h.exchange(h.author.timing(0, 2000.0f, &start, {cruise(100000)})).reason, 0);
  h.loopAt(150000);
  EXPECT_EQ(h.exchange(h.author.halt(HALT_BRAKE_AT, 180000)).reason, 0);  // at 8 mm, 2.5 mm to stop
  for (uint32_t t = 150000; t <= 400000; t += 1000) h.loopAt(t);
  EXPECT_EQ(h.device->state(), state::STOPPED);
  EXPECT_EQ(h.device->positionUnits(0), mm(10));
  EXPECT_EQ(h.exchange(h.author.geometry(1, nullptr, {{10.0f, {mm(20)}}}, 1)).reason, 0);
  lateThenRestart(h, 1, mm(10), mm(20), state::STOPPED);
}

TEST(Timing, ContinuationOfNothingIsMalformed) {
  MAXL_TrackPositionLinear x("x", position);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  h.at(50000);
  EXPECT_EQ(h.exchange(h.author.geometry(0, &ORIGIN1, {{10.0f, {mm(10)}}, {10.0f, {mm(20)}}}, 1)).reason, 0);
  // No timing yet in the session.
  Answer a = h.exchange(h.author.timing(0, 1000.0f, nullptr, {cruise(100000)}));
  EXPECT_EQ(a.reason, nack::MALFORMED);
  EXPECT_EQ(a.detail, type::TIMING);
  EXPECT_FALSE(h.device->statusFlags() & status_flag::LATE);
  uint32_t start = 100000;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {trapezoid(10, 0, 100, 0, 1000)})).reason, 0);
  // Overlapping the timing queued is malformed too.
  uint32_t early = 250000;
  EXPECT_EQ(h.exchange(h.author.timing(1, 1000.0f, &early, {cruise(100000)})).reason, nack::MALFORMED);
  for (uint32_t t = 100000; t <= 400000; t += 1000) h.loopAt(t);
  EXPECT_EQ(h.device->positionUnits(0), mm(10));
  // After HALT mode 0 the timing before is forgotten: nothing to continue again.
  EXPECT_EQ(h.exchange(h.author.halt(HALT_NOW, 0)).reason, 0);
  std::vector<int32_t> here = {mm(10)};
  EXPECT_EQ(h.exchange(h.author.geometry(7, &here, {{10.0f, {mm(20)}}}, 1)).reason, 0);
  a = h.exchange(h.author.timing(7, 1000.0f, nullptr, {cruise(100000)}));
  EXPECT_EQ(a.reason, nack::MALFORMED);
  EXPECT_EQ(a.detail, type::TIMING);
  EXPECT_FALSE(h.device->statusFlags() & status_flag::LATE);
  EXPECT_EQ(h.device->state(), state::HALTED);
  start = h.now() + 50000;
  EXPECT_EQ(h.exchange(h.author.timing(7, 1000.0f, &start, {trapezoid(10, 0, 100, 0, 1000)})).reason, 0);
  h.loopAt(start + 400000);
  EXPECT_EQ(h.device->positionUnits(0), mm(20));
  // A new session forgets it too.
  h.open({{0, kind::POSITION, 0}});
  EXPECT_EQ(h.exchange(h.author.geometry(0, &here, {{10.0f, {mm(20)}}}, 1)).reason, 0);
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, nullptr, {cruise(100000)})).reason, nack::MALFORMED);
}
