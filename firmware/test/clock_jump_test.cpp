// The clock-jump check (device.cpp readClock(), config.h MAXL_CLOCK_JUMP_US,
// protocol §6 "Clock jumps"). Built into its own test program with the check
// on (the default on boards and in wasm): the main suite turns it off, since
// its tests jump the virtual clock between loops on purpose.
#include <gtest/gtest.h>

#include <cmath>

#include "support/harness.h"
#include "support/reference.h"

static_assert(MAXL_CLOCK_JUMP_US == 10000, "this program tests the default bound");

using namespace maxl_fw;
using namespace maxltest;

namespace {
void onPosition(float, float) {}

// 100 mm at 100 mm/s on one slot, starting at 100 000 µs, the device looping
// every 500 µs up to `until` (device time). Returns the harness's last time.
uint32_t startCruise(Harness& h, uint32_t until) {
  h.open({{0, kind::POSITION, 0}});
  std::vector<int32_t> p0 = {mm(0)};
  EXPECT_EQ(h.exchange(h.author.geometry(0, &p0, {{100.0f, {mm(100)}}, {50.0f, {mm(150)}}}, 1)).reason, 0);
  uint32_t start = 100000;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {cruise(1000000)})).reason, 0);
  uint32_t t = h.now();
  for (; t < until; t += 500) h.loopAt(t);
  return t;
}

uint8_t flagsOfLastStatus(Harness& h) {
  uint8_t flags = 0;
  for (auto& p : h.take()) {
    if (p.type != type::STATUS) continue;
    msg::Status s;
    EXPECT_TRUE(msg::parse(p.payload.data(), (uint8_t)p.payload.size(), s));
    flags = s.flags;
  }
  return flags;
}

// micros() leaps by `jump` µs beyond the loop's 500 µs at device time 400 000
// (30 mm along), so the read steps by 500 + jump from the last: the
// position does not leap, the flag goes out at once, more TIMING is refused,
// and the device runs out of what it holds and brakes to rest on the path.
void expectMended(int32_t jump) {
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  uint32_t t = startCruise(h, 400000);
  h.take();
  int32_t before = h.device->positionUnits(0);
  EXPECT_NEAR(before, mm(29.95), 8);
  EXPECT_FALSE(h.device->statusFlags() & status_flag::CLOCK_JUMP);
  // The counter leaps: the next loop reads t + jump instead of t.
  const uint32_t skew = (uint32_t)jump + 500;  // micros() − the mended clock from now on
  h.loopAt(t + (uint32_t)jump);
  EXPECT_EQ(h.device->positionUnits(0), before) << "evaluated at the jumped time";
  EXPECT_EQ(h.device->now(), t - 500) << "the clock goes on from the last read";
  EXPECT_TRUE(h.device->statusFlags() & status_flag::CLOCK_JUMP);
  EXPECT_TRUE(flagsOfLastStatus(h) & status_flag::CLOCK_JUMP) << "reported at once";
  // On from there, on the mended clock: 0.05 mm per 500 µs loop.
  for (int k = 1; k <= 10; k++) {
    h.loopAt(t + (uint32_t)jump + 500u * (uint32_t)k);
    EXPECT_NEAR(h.device->positionUnits(0), before + mm(0.05 * k), 8) << k;
  }
  // No more timing: the continuation of segment 0 is refused with CLOCK_JUMP.
  Answer a = h.exchange(h.author.timing(1, 1000.0f, nullptr, {cruise(500000)}));
  EXPECT_EQ(a.reason, nack::CLOCK_JUMP);
  EXPECT_EQ(a.detail, 1);
  // Runs segment 0 to its end (device time 1 100 000, mended), then brakes
  // along the untimed segment 1 at 1000 mm/s²: 100²/2000 = 5 mm, to rest at 105 mm.
  uint32_t mendedEnd = 1100000;
  for (uint32_t u = h.device->now(); (int32_t)(u - (mendedEnd + 200000)) < 0; u += 500) {
    h.loopAt(u + skew);
    if ((int32_t)(u - (mendedEnd - 1000)) < 0) {
      ASSERT_EQ(h.device->state(), state::RUNNING) << u;
    }
  }
  EXPECT_EQ(h.device->state(), state::STOPPED);
  EXPECT_NEAR(h.device->positionUnits(0), mm(105), 40);
  // STATUS and PONG stamps are on the mended clock too.
  h.take();
  h.send(h.author.ping(9));
  for (auto& p : h.take()) {
    if (p.type != type::PONG) continue;
    msg::Pong pong;
    ASSERT_TRUE(msg::parse(p.payload.data(), (uint8_t)p.payload.size(), pong));
    EXPECT_EQ(pong.txTime, h.now() - skew);
  }
  // A new session clears the flag and takes timing again, on the same (mended) clock.
  h.open({{0, kind::POSITION, 0}});
  EXPECT_FALSE(h.device->statusFlags() & status_flag::CLOCK_JUMP);
  std::vector<int32_t> p0 = {mm(105)};
  EXPECT_EQ(h.exchange(h.author.geometry(0, &p0, {{10.0f, {mm(115)}}}, 1)).reason, 0);
  uint32_t start = h.now() - skew + 20000;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {cruise(100000)})).reason, 0);
  for (uint32_t u = h.now(); (int32_t)(u - skew - start - 150000) < 0; u += 500) h.loopAt(u);
  EXPECT_EQ(h.device->positionUnits(0), mm(115));
  EXPECT_FALSE(h.device->statusFlags() & status_flag::CLOCK_JUMP);
}
}  // namespace

TEST(ClockJump, ForwardLeapIsMendedReportedAndRunsOutOnThePath) { expectMended(50000); }

TEST(ClockJump, BackwardStepIsMendedReportedAndRunsOutOnThePath) { expectMended(-5000); }

TEST(ClockJump, JustPastTheBoundIsAJump) { expectMended((int32_t)MAXL_CLOCK_JUMP_US + 1 - 500); }

TEST(ClockJump, LoopsUpToTheBoundApartAreNotAJump) {
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  uint32_t t = startCruise(h, 200000) - 500;  // the last read
  // Gaps of exactly the bound, and of none (two loops at one instant).
  for (int k = 0; k < 20; k++) {
    t += MAXL_CLOCK_JUMP_US;
    h.loopAt(t);
    h.loopAt(t);
  }
  EXPECT_FALSE(h.device->statusFlags() & status_flag::CLOCK_JUMP);
  EXPECT_EQ(h.device->now(), t);
  EXPECT_NEAR(h.device->positionUnits(0), mm(0.1 * ((t - 100000) / 1000.0)), 8);
}

TEST(ClockJump, NotCheckedWithoutTiming) {
  MAXL_TrackPositionLinear x("x", onPosition);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  // Idle: a loop may come seconds later (a sketch busy elsewhere); the clock is not watched.
  h.loopAt(h.now() + 3000000);
  h.loopAt(h.now() - 1000);
  EXPECT_FALSE(h.device->statusFlags() & status_flag::CLOCK_JUMP);
  std::vector<int32_t> p0 = {mm(0)};
  EXPECT_EQ(h.exchange(h.author.geometry(0, &p0, {{1.0f, {mm(1)}}}, 1)).reason, 0);
  uint32_t start = h.now() + 10000;
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {cruise(10000)})).reason, 0);
}
