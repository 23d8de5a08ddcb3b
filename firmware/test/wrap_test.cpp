// A job that crosses the 71.6-minute wrap of the u32 µs clock (protocol §1).
#include <gtest/gtest.h>

#include <cmath>

#include "support/harness.h"
#include "support/reference.h"

using namespace maxl_fw;
using namespace maxltest;

namespace {
void onPosition(float, float) {}
std::vector<std::pair<uint32_t, float>> gEvents;
uint32_t gNow;
void onEvent(float v) { gEvents.push_back({gNow, v}); }
}  // namespace

TEST(Wrap, SegmentsEventsAndStatusAcrossTheWrap) {
  MAXL_TrackPositionLinear x("x", onPosition);
  MAXL_TrackEvent e("e", onEvent);
  Harness h;
  const uint32_t start = 0xFFFFFFFFu - 250000;  // 0.25 s before the wrap
  h.at(start - 100000);
  h.open({{0, kind::POSITION, 0}, {1, kind::EVENT, 0}});
  msg::TimingSegment first = trapezoid(40.0, 0, 100, 100, 1000);
  msg::TimingSegment second = trapezoid(40.0, 100, 100, 0, 1000);
  std::vector<int32_t> p0 = {mm(0)};
  EXPECT_EQ(h.exchange(h.author.geometry(0, &p0, {{40.0f, {mm(40)}}, {40.0f, {mm(80)}}}, 1)).reason, 0);
  uint32_t s = start;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &s, {first, second})).reason, 0);
  uint32_t secondStart = start + durationOf(first);  // after the wrap
  ASSERT_LT(secondStart, start);
  EXPECT_EQ(h.exchange(h.author.events(0, 0, 0, {{200000, 1.0f}, {300000, 2.0f}})).reason, 0);
  EXPECT_EQ(h.exchange(h.author.events(1, 0, 0, {{1000, 3.0f}})).reason, 0);
  gEvents.clear();
  uint32_t lastStatus = 0;
  int statuses = 0;
  uint32_t end = secondStart + durationOf(second);
  for (uint32_t t = start - 1000; t != end + 200000; t += 500) {
    gNow = t;
    h.loopAt(t);
    bool inFirst = (int32_t)(t - secondStart) < 0;
    const msg::TimingSegment& seg = inFirst ? first : second;
    uint32_t segStart = inFirst ? start : secondStart;
    double tau = (double)(int32_t)(t - segStart);
    double expected = (inFirst ? 0 : 40) + 40 * referenceSigma(seg, tau).sigma;
    if ((int32_t)(t - start) < 0) expected = 0;
    ASSERT_NEAR(h.device->positionUnits(0), mm(expected), positionToleranceUnits(std::max(0.0, tau), mm(40))) << t;
    for (auto& p : h.take()) {
      if (p.type != type::STATUS) continue;
      msg::Status st;
      ASSERT_TRUE(msg::parse(p.payload.data(), (uint8_t)p.payload.size(), st));
      if (statuses++ && st.state != state::IDLE) {
        EXPECT_LE(st.now - lastStatus, 100000u) << "periodic status across the wrap";
      }
      lastStatus = st.now;
    }
  }
  EXPECT_EQ(h.device->positionUnits(0), mm(80));
  EXPECT_EQ(h.device->state(), state::IDLE);
  ASSERT_EQ(gEvents.size(), 3u);
  EXPECT_EQ(gEvents[0].first, start + 200000);
  EXPECT_EQ(gEvents[1].first, start + 300000);  // wrapped
  EXPECT_EQ(gEvents[2].first, secondStart + 1000);
  EXPECT_GT(statuses, 5);
}

TEST(Wrap, LateIsJudgedWrapSafe) {
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  h.at(100);  // just after the wrap
  h.open({{0, kind::POSITION, 0}});
  std::vector<int32_t> p0 = {0};
  EXPECT_EQ(h.exchange(h.author.geometry(0, &p0, {{1.0f, {mm(1)}}}, 1)).reason, 0);
  uint32_t before = 0xFFFFFF00u;  // 356 µs ago
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &before, {trapezoid(1, 0, 10, 0, 100)})).reason, nack::LATE_SEGMENT);
  uint32_t after = 0x00001000u;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &after, {trapezoid(1, 0, 10, 0, 100)})).reason, 0);
}
