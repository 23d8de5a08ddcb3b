// Motion's shortcuts at segment and phase boundaries give the same numbers as
// crossing every boundary one by one.
//
// A tick that lands past several boundaries takes shortcuts (motion.cpp):
// a last phase that is over by `now` is not crossed (the segment ends at its p1
// anyway), and the next segment's tracks after a short phase 0 come from
// prepareNext(), worked out in an earlier tick (enterAfterPhase0()). Ticking
// every 1 µs crosses the boundaries one at a time (at a tick exactly on a
// boundary, nothing after it is due yet); ticking every 7, 20 or 53 µs takes
// the shortcuts. The positions must agree to the unit at every sparse tick,
// for paths of short segments whose phases are 0 to 3 µs at the start, the end
// and the middle, with the timing given all at once or a few segments at a
// time (which re-prepares), and with a segment dropped and replaced after it
// was prepared (REPLACE_TAIL).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "maxl/motion/motion.h"
#include "maxl/motion/profile.h"
#include "maxl/wire/protocol.h"

using namespace maxl_fw;

namespace {

struct Piece {
  uint8_t kinds[3];  // phase kinds (phase::ACCELERATE, CRUISE, DECELERATE)
  uint32_t durations[3];
  uint8_t count;
  int32_t delta[2];  // units, per slot
};

// A deterministic mix of short pieces: 0.3–0.8 mm, 1–4 ms, and phases of
// 0–3 µs where rounding puts them (first, last, middle), or none.
std::vector<Piece> makePieces(uint32_t seed, int n) {
  std::vector<Piece> out;
  uint32_t x = seed;
  auto next = [&x](uint32_t m) {
    x = x * 1664525u + 1013904223u;
    return (x >> 8) % m;
  };
  for (int i = 0; i < n; i++) {
    Piece p;
    uint32_t longer = 1000 + next(3000);
    uint32_t tiny = next(4);
    switch (next(6)) {
      case 0:  // tiny acceleration, then braking
        p.count = 2;
        p.kinds[0] = phase::ACCELERATE, p.durations[0] = tiny;
        p.kinds[1] = phase::DECELERATE, p.durations[1] = longer;
        break;
      case 1:  // acceleration, then a tiny brake
        p.count = 2;
        p.kinds[0] = phase::ACCELERATE, p.durations[0] = longer;
        p.kinds[1] = phase::DECELERATE, p.durations[1] = tiny;
        break;
      case 2:  // tiny, cruise, tiny
        p.count = 3;
        p.kinds[0] = phase::ACCELERATE, p.durations[0] = tiny;
        p.kinds[1] = phase::CRUISE, p.durations[1] = longer;
        p.kinds[2] = phase::DECELERATE, p.durations[2] = next(4);
        break;
      case 3:  // a tiny middle phase
        p.count = 3;
        p.kinds[0] = phase::ACCELERATE, p.durations[0] = longer / 2;
        p.kinds[1] = phase::CRUISE, p.durations[1] = tiny;
        p.kinds[2] = phase::DECELERATE, p.durations[2] = longer / 2;
        break;
      case 4:  // cruise only
        p.count = 1;
        p.kinds[0] = phase::CRUISE, p.durations[0] = longer;
        break;
      default:  // cruise, then a tiny acceleration
        p.count = 2;
        p.kinds[0] = phase::CRUISE, p.durations[0] = longer;
        p.kinds[1] = phase::ACCELERATE, p.durations[1] = tiny;
        break;
    }
    for (uint8_t k = p.count; k < 3; k++) p.kinds[k] = phase::CRUISE, p.durations[k] = 0;
    p.delta[0] = (int32_t)next(52429) - 26214 + 32768;  // 0.1–0.9 mm
    p.delta[1] = (int32_t)next(52429) - 26214;
    out.push_back(p);
  }
  return out;
}

const float ACCEL = 3000.0f;  // mm/s²

// Appends piece p (geometry and timing, as the GEOMETRY and TIMING handlers
// would) starting at `start`; returns its end.
uint32_t queuePiece(Motion& motion, const Piece& p, uint32_t start) {
  SegmentQueue& q = motion.queue();
  uint8_t index = q.count();
  Segment& s = q.append();
  float dx = (float)p.delta[0] / 65536.0f, dy = (float)p.delta[1] / 65536.0f;
  s.length = sqrtf(dx * dx + dy * dy);
  for (uint8_t i = 0; i < 2; i++) s.p1[i] = motion.startOf(index, i) + p.delta[i];
  s.shape = 0;
  for (uint8_t k = 0; k < 3; k++) {
    s.shape |= (uint8_t)(p.kinds[k] << (2 * k));
    s.durations[k] = p.durations[k];
  }
  s.phaseCount = p.count;
  s.alpha = ACCEL / s.length;
  float peak, end;
  EXPECT_TRUE(solveProfile(s, peak, end));
  for (uint8_t i = 0; i < 2; i++)
    EXPECT_TRUE(slotCoefficients((float)p.delta[i], s.nu0, peak, s.alpha, s.b0[i], s.cmag[i]));
  s.start = start;
  return start + s.duration();
}

struct PathRun {
  Motion motion;
  std::vector<Piece> pieces;
  size_t queued = 0;
  size_t timed = 0;
  uint32_t nextStart;
  uint8_t batch;  // timing given this many segments at a time (0: all at once)

  PathRun(const std::vector<Piece>& p, uint32_t start, uint8_t timingBatch) : pieces(p), nextStart(start), batch(timingBatch) {
    motion.reset();
    motion.setActiveSlots(2);
    int32_t p0[2] = {0, 0};
    motion.setBase(p0, 2);
    motion.setStopDecel(ACCEL);
    feed();
  }
  // Keeps the queue full; timing goes with the geometry, or `batch` at a time.
  void feed() {
    while (queued < pieces.size() && motion.queue().free() > 0) {
      nextStart = queuePiece(motion, pieces[queued++], nextStart);
      if (batch == 0 || queued % batch == 0 || queued == pieces.size()) motion.markTimed(motion.queue().count());
    }
  }
  void tick(uint32_t t) {
    motion.tick(t);
    feed();
  }
};

void expectSame(uint32_t seed, uint32_t period, uint8_t batch) {
  std::vector<Piece> pieces = makePieces(seed, 150);
  const uint32_t start = 1000;
  PathRun dense(pieces, start, batch);
  PathRun sparse(pieces, start, batch);
  uint32_t t = start;
  uint32_t checked = 0;
  // Until the path is over: it ends at rest (IDLE) or, its last piece ending
  // in motion, stopped dead at its end (STOPPED, no geometry to brake along).
  auto running = [](const Motion& m) { return m.mode() != Motion::IDLE && m.mode() != Motion::STOPPED; };
  for (; running(dense.motion) || t == start; t++) {
    ASSERT_LT(t - start, 20000000u) << "the path never ended";
    dense.tick(t);
    if ((t - start) % period) continue;
    sparse.tick(t);
    for (uint8_t i = 0; i < 2; i++)
      ASSERT_EQ(sparse.motion.position(i), dense.motion.position(i))
          << "seed " << seed << ", every " << period << " µs, timing by " << (int)batch << ": slot " << (int)i
          << " at t = " << t;
    checked++;
  }
  sparse.tick(t);
  EXPECT_EQ(sparse.motion.mode(), dense.motion.mode());
  for (uint8_t i = 0; i < 2; i++) EXPECT_EQ(sparse.motion.position(i), dense.motion.position(i));
  EXPECT_GT(checked, 1000u);
}

}  // namespace

TEST(MotionShortcuts, SparseTicksMatchTicksAtEveryMicrosecond) {
  for (uint32_t period : {7u, 20u, 53u})
    for (uint32_t seed : {1u, 2u, 3u}) expectSame(seed, period, 0);
}

TEST(MotionShortcuts, TimingGivenAFewSegmentsAtATime) {
  for (uint8_t batch : {1, 2, 5})
    for (uint32_t period : {7u, 20u}) expectSame(11u + batch, period, batch);
}

// REPLACE_TAIL after prepareNext() worked out the segment after the head: the
// replacement, with the same id, must not use what was prepared for the old one.
TEST(MotionShortcuts, ReplacedSegmentIsNotEnteredWithStaleWork) {
  std::vector<Piece> first = makePieces(21, 2);
  std::vector<Piece> other = makePieces(22, 40);
  first[0].count = 1;  // the head cruises 3 ms: its second tick is an ordinary one, which prepares first[1]
  first[0].kinds[0] = phase::CRUISE, first[0].durations[0] = 3000;
  first[0].durations[1] = first[0].durations[2] = 0;
  first[1].count = 2;  // a tiny phase 0 after the head, so it is prepared
  first[1].kinds[0] = phase::ACCELERATE, first[1].durations[0] = 2;
  first[1].kinds[1] = phase::DECELERATE, first[1].durations[1] = 3000;
  other[0] = first[1];
  other[0].delta[0] += 30000;  // a different segment in its place

  // dense reference: the head, then `other` from the start
  std::vector<Piece> expected;
  expected.push_back(first[0]);
  for (const Piece& p : other) expected.push_back(p);

  for (uint32_t period : {20u, 53u}) {
    PathRun dense(expected, 1000, 0);
    PathRun sparse(first, 1000, 0);
    // let the sparse run prepare first[1], then replace it (and all after the head)
    uint32_t t = 1000;
    sparse.tick(t);
    sparse.tick(t + period);
    ASSERT_EQ(sparse.motion.mode(), Motion::RUNNING);
    sparse.motion.dropFrom(1);
    sparse.pieces = expected;
    sparse.queued = 1;
    sparse.nextStart = sparse.motion.queue().head().end();
    sparse.feed();
    for (; (dense.motion.mode() != Motion::IDLE && dense.motion.mode() != Motion::STOPPED) || t == 1000; t++) {
      ASSERT_LT(t, 20000000u) << "the path never ended";
      dense.tick(t);
      if ((t - 1000) % period || t == 1000 || t == 1000 + period) continue;
      sparse.tick(t);
      for (uint8_t i = 0; i < 2; i++)
        ASSERT_EQ(sparse.motion.position(i), dense.motion.position(i)) << "every " << period << " µs, t = " << t;
    }
  }
}
