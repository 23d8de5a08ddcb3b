// Event tracks (protocol §4 EVENTS): times, order, continuation, capacity.
#include <gtest/gtest.h>

#include <cmath>

#include "support/harness.h"

using namespace maxl_fw;
using namespace maxltest;

namespace {
struct Seen {
  uint32_t t;
  int slot;
  float v;
};
std::vector<Seen> gSeen;
uint32_t gNow = 0;
void onA(float v) { gSeen.push_back({gNow, 0, v}); }
void onB(float v) { gSeen.push_back({gNow, 1, v}); }

void runTo(Harness& h, uint32_t from, uint32_t to) {
  for (uint32_t t = from; t <= to; t++) {
    gNow = t;
    h.loopAt(t);
  }
}

void twoSegments(Harness& h) {
  std::vector<int32_t> none;
  EXPECT_EQ(h.exchange(h.author.geometry(0, &none, {{1.0f, {}}, {1.0f, {}}}, 0)).reason, 0);
  uint32_t start = 1000;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {cruise(1000), cruise(1000)})).reason, 0);
}
}  // namespace

TEST(Events, FireAtTheirTimeInOrderPerSlot) {
  MAXL_TrackEvent a("a", onA);
  MAXL_TrackEvent b("b", onB);
  Harness h;
  h.open({{0, kind::EVENT, 0}, {1, kind::EVENT, 3}});
  twoSegments(h);
  EXPECT_EQ(h.exchange(h.author.events(0, 0, 0, {{0, 1.0f}, {500, 2.0f}, {500, 3.0f}})).reason, 0);
  EXPECT_EQ(h.exchange(h.author.events(0, 3, 0, {{100, 10.0f}, {999, 11.0f}})).reason, 0);
  EXPECT_EQ(h.exchange(h.author.events(1, 0, 0, {{1, 4.0f}})).reason, 0);
  EXPECT_EQ(h.exchange(h.author.events(1, 3, 0, {{0, 12.0f}, {1000, 13.0f}})).reason, 0);
  gSeen.clear();
  runTo(h, 900, 3100);
  std::vector<Seen> expected = {{1000, 0, 1}, {1100, 1, 10}, {1500, 0, 2}, {1500, 0, 3}, {1999, 1, 11},
                                {2000, 1, 12}, {2001, 0, 4}, {3000, 1, 13}};
  ASSERT_EQ(gSeen.size(), expected.size());
  for (size_t i = 0; i < expected.size(); i++) {
    EXPECT_EQ(gSeen[i].t, expected[i].t) << i;
    EXPECT_EQ(gSeen[i].slot, expected[i].slot) << i;
    EXPECT_EQ(gSeen[i].v, expected[i].v) << i;
  }
  EXPECT_EQ(a.value(), 4.0f);
}

TEST(Events, LateLoopCallsFireEveryMissedChangeInOrder) {
  MAXL_TrackEvent a("a", onA);
  Harness h;
  h.open({{0, kind::EVENT, 0}});
  twoSegments(h);
  EXPECT_EQ(h.exchange(h.author.events(0, 0, 0, {{0, 1.0f}, {100, 2.0f}, {200, 3.0f}})).reason, 0);
  gSeen.clear();
  gNow = 5000;
  h.loopAt(5000);
  ASSERT_EQ(gSeen.size(), 3u);
  EXPECT_EQ(gSeen[2].v, 3.0f);
}

TEST(Events, ContinuationFramesAndTheirChecks) {
  MAXL_TrackEvent a("a", onA);
  Harness h;
  h.open({{0, kind::EVENT, 0}});
  twoSegments(h);
  EXPECT_EQ(h.exchange(h.author.events(0, 0, 0, {{0, 1.0f}, {10, 2.0f}})).reason, 0);
  EXPECT_EQ(h.exchange(h.author.events(0, 0, 3, {{20, 3.0f}})).reason, nack::MALFORMED);  // skips index 2
  EXPECT_EQ(h.exchange(h.author.events(0, 0, 2, {{5, 3.0f}})).reason, nack::MALFORMED);   // offsets fall
  EXPECT_EQ(h.exchange(h.author.events(0, 0, 2, {{20, 3.0f}})).reason, 0);
  EXPECT_EQ(h.exchange(h.author.events(1, 0, 1, {{0, 3.0f}})).reason, nack::MALFORMED);   // new segment starts at 0
  EXPECT_EQ(h.exchange(h.author.events(1, 0, 0, {{1001, 3.0f}})).reason, nack::MALFORMED); // past the segment's end
  EXPECT_EQ(h.exchange(h.author.events(1, 0, 0, {{1000, 3.0f}})).reason, 0);
  EXPECT_EQ(h.exchange(h.author.events(0, 0, 3, {{30, 3.0f}})).reason, nack::MALFORMED);  // segments in order
  EXPECT_EQ(h.exchange(h.author.events(0, MAXL_EVENT_SLOTS, 0, {{0, 1.0f}})).reason, nack::MALFORMED);
  EXPECT_EQ(h.exchange(h.author.events(0, 0, 0, {})).reason, nack::MALFORMED);
}

TEST(Events, NeedATimedSegment) {
  MAXL_TrackEvent a("a", onA);
  Harness h;
  h.open({{0, kind::EVENT, 0}});
  std::vector<int32_t> none;
  EXPECT_EQ(h.exchange(h.author.geometry(0, &none, {{1.0f, {}}, {1.0f, {}}}, 0)).reason, 0);
  uint32_t start = 1000;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {cruise(1000)})).reason, 0);
  Answer untimed = h.exchange(h.author.events(1, 0, 0, {{0, 1.0f}}));
  EXPECT_EQ(untimed.reason, nack::UNKNOWN_SEGMENT);
  EXPECT_EQ(untimed.detail, 1);
  EXPECT_EQ(h.exchange(h.author.events(7, 0, 0, {{0, 1.0f}})).reason, nack::UNKNOWN_SEGMENT);
}

TEST(Events, QueueFullAddsNothing) {
  MAXL_TrackEvent a("a", onA);
  Harness h;
  h.open({{0, kind::EVENT, 0}});
  std::vector<int32_t> none;
  EXPECT_EQ(h.exchange(h.author.geometry(0, &none, {{1.0f, {}}}, 0)).reason, 0);
  uint32_t start = 1000;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {cruise(100000)})).reason, 0);
  uint16_t index = 0;
  while (index + 8 <= MAXL_EVENT_CAPACITY) {
    std::vector<msg::EventEntry> batch;
    for (int k = 0; k < 8; k++) batch.push_back({(uint32_t)(index + k) * 10, (float)(index + k)});
    EXPECT_EQ(h.exchange(h.author.events(0, 0, index, batch)).reason, 0);
    index += 8;
  }
  // One entry more than the room left: refused whole, with the room left in the detail.
  const uint16_t room = MAXL_EVENT_CAPACITY - index;
  std::vector<msg::EventEntry> more;
  for (int k = 0; k < room + 1; k++) more.push_back({(uint32_t)(index + k) * 10, -1.0f});
  Answer full = h.exchange(h.author.events(0, 0, index, more));
  EXPECT_EQ(full.reason, nack::QUEUE_FULL);
  EXPECT_EQ(full.detail, room);
  EXPECT_TRUE(h.device->statusFlags() & status_flag::EVENT_OVERFLOW);

  // Nothing of it was added: the track still expects entry `index` next, and exactly
  // `room` entries still fit (one more would not).
  std::vector<msg::EventEntry> fits(more.begin(), more.begin() + room);
  for (auto& e : fits) e.value = (float)(&e - &fits[0] + index);
  if (room > 0) {
    EXPECT_EQ(h.exchange(h.author.events(0, 0, (uint16_t)(index + 1), {fits[0]})).reason, nack::MALFORMED);  // not where the track is
    EXPECT_EQ(h.exchange(h.author.events(0, 0, index, fits)).reason, 0);
  }
  EXPECT_EQ(h.exchange(h.author.events(0, 0, MAXL_EVENT_CAPACITY, {{(uint32_t)MAXL_EVENT_CAPACITY * 10, -1.0f}})).reason, nack::QUEUE_FULL);

  // And the segment runs exactly the accepted changes, in order: 0, 1, …, capacity − 1, never −1.
  gSeen.clear();
  runTo(h, 0, 1000 + MAXL_EVENT_CAPACITY * 10 + 10);
  ASSERT_EQ(gSeen.size(), (size_t)MAXL_EVENT_CAPACITY);
  for (size_t k = 0; k < gSeen.size(); k++) {
    EXPECT_EQ(gSeen[k].v, (float)k);
    EXPECT_EQ(gSeen[k].t, 1000 + k * 10);
  }
}
