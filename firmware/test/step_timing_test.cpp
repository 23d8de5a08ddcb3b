// Timed stepping (readers/step_timer.h, MAXL_Stepper with the step timer):
// the window maths against an exact (double) path, the channel and its
// virtual timer, and a whole device whose stepper steps from the timer while
// loop() runs late, streams, halts and brakes.
//
// "On time" is the benchmark's definition (bench/firmware.mjs): every step
// present, none before its ideal time (the exact position crossing the
// step's threshold), none later than one step period after it. The tests
// hold the timed stepper to more: its lag must stay within what the design
// allows (stepper.h: the window's bend c·W²/4 <= s/2^MAXL_STEP_BEND_SHIFT plus
// MAXL_STEP_LAG_UNITS, over the speed).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "support/harness.h"
#include "maxl/time/wrap.h"
#include "support/reference.h"

using namespace maxl_fw;
using namespace maxltest;

namespace {


struct Edge {
  double us;  // exact time of the rising edge (the host timer writes pins at half µs)
  bool backward;
};

// Rising edges of `stepPin`, with the DIR level at each (`forwardLevel` = DIR's level going forward).
std::vector<Edge> stepEdges(uint8_t stepPin, uint8_t dirPin, bool forwardLevel = true) {
  std::vector<Edge> out;
  const host::PinWrite* log = host::pinLog();
  int last = 0;
  int dir = -1;
  for (size_t i = 0; i < host::pinLogLength(); i++) {
    if (log[i].pin == dirPin) dir = log[i].value;
    if (log[i].pin != stepPin) continue;
    if (log[i].value && !last) out.push_back(Edge{(double)log[i].tick / 2.0, dir != (int)forwardLevel});
    last = log[i].value;
  }
  EXPECT_FALSE(host::pinLogOverflowed());
  return out;
}

// A path made of timed segments on one slot, evaluated exactly (double).
struct Path {
  struct Piece {
    msg::TimingSegment timing;
    double start;  // device µs (unwrapped)
    double p0, p1; // units
  };
  std::vector<Piece> pieces;
  double end() const {
    const Piece& p = pieces.back();
    return p.start + durationOf(p.timing);
  }
  double at(double t) const {
    const Piece* c = &pieces.front();
    for (const Piece& p : pieces)
      if (t >= p.start) c = &p;
    return c->p0 + (c->p1 - c->p0) * referenceSigma(c->timing, t - c->start).sigma;
  }
  double speed(double t) const {  // units/µs
    const Piece* c = &pieces.front();
    for (const Piece& p : pieces)
      if (t >= p.start) c = &p;
    double tau = t - c->start;
    if (tau < 0 || tau > durationOf(c->timing)) return 0;
    return std::fabs((c->p1 - c->p0) * referenceSigma(c->timing, tau).nu * 1e-6);
  }
};

// When the exact path first reaches `threshold` going `up` (bisection on a
// monotonic path between lo and hi).
double crossing(const Path& path, double threshold, bool up, double lo, double hi) {
  for (int i = 0; i < 80; i++) {
    double mid = 0.5 * (lo + hi);
    bool reached = up ? path.at(mid) >= threshold : path.at(mid) < threshold;
    if (reached)
      hi = mid;
    else
      lo = mid;
  }
  return hi;
}

struct Verdict {
  int expected = 0, got = 0, early = 0, late = 0, tooLaggy = 0;
  double maxLagUs = -1e9, minLagUs = 1e9, worstLagOverPeriod = 0;
};

// Checks monotonic motion from step n0 for `steps` steps (signed): every step
// there, none early, none later than a period; `allowedLag(units)` bounds the
// lag in units of distance (lag·speed).
Verdict judge(const Path& path, const std::vector<Edge>& edges, double s, int32_t n0, int32_t steps,
              double slackUnits) {
  Verdict v;
  bool up = steps > 0;
  v.expected = std::abs(steps);
  v.got = (int)edges.size();
  double lo = path.pieces.front().start, hi = path.end();
  for (int k = 1; k <= v.expected; k++) {
    double threshold = up ? (n0 + k - 0.5) * s : (n0 - k + 0.5) * s;
    double ideal = crossing(path, threshold, up, lo, hi);
    if (k > (int)edges.size()) break;
    double lag = edges[k - 1].us - ideal;
    double speed = path.speed(ideal + 1e-3);
    double period = speed > 1e-12 ? s / speed : 1e12;
    v.maxLagUs = std::max(v.maxLagUs, lag);
    v.minLagUs = std::min(v.minLagUs, lag);
    v.worstLagOverPeriod = std::max(v.worstLagOverPeriod, lag / period);
    if (lag < -1e-6) v.early++;
    if (lag > period) v.late++;
    // the design's bound: lag·speed <= bend + margin (+ the half count of the
    // timer and the fixed-point evaluation's few units)
    if (lag > 0.5 + 1e-6 && lag * speed > slackUnits) v.tooLaggy++;
    EXPECT_EQ(edges[k - 1].backward, !up) << k;
  }
  return v;
}

// A device with one stepper on slot 0, 80 steps/mm, timed or polled.
struct Rig {
  MAXL_Stepper stepper;
  Harness h;
  Path path;
  uint32_t now = 0;
  // The device clock starts at `startUs` (set in steps the virtual timer follows).
  explicit Rig(bool timed, uint32_t startUs = 0, float stepsPerMm = 80.0f) : stepper("stepper", 2, 5, stepsPerMm) {
    EXPECT_EQ(stepper.useStepTimer(timed), timed);
    host::setMicros(startUs / 2);
    host::setMicros(startUs);
    now = startUs;
    h.open({{0, kind::POSITION, 0}});
  }
  // Unwrapped device µs (the path's times) to the device clock.
  static uint32_t clock(double t) { return (uint32_t)(uint64_t)t; }
  // Runs loop() at `loops` (device µs, rising), the step timer in between.
  void runUntil(uint32_t end, const std::function<uint32_t(uint32_t)>& nextLoop) {
    while (timeBefore(now, end)) {
      uint32_t next = nextLoop(now);
      host::runStepTimer(next);
      now = next;
      h.loop();
    }
  }
  void send(const Bytes& frame) {
    // frames arrive at `now`; the timer keeps running while loop() takes them
    host::runStepTimer(now);
    host::pushRx(frame.data(), frame.size());
    while (host::rxPending()) {
      now += 20;
      host::runStepTimer(now);
      h.loop();
    }
  }
};

}  // namespace

// ---------------------------------------------------------------- the channel

TEST(StepChannel, EmitsRunsAtTheirCountsAndTakesBackTheRest) {
  host::reset();
  MAXL_StepGenerator g(2, 5, 80.0f);
  g.begin();
  ASSERT_TRUE(StepTimer::attach(&g.channel()));
  host::setMicros(1000);
  host::clearPinLog();
  uint32_t base = StepTimer::ticksAt(1100);
  // 3 steps from 1100 µs every 12.25 µs, then 2 back from 1200.5 µs every 10 µs
  g.channel().push(base, (uint32_t)(24.5 * 65536), 3, false);
  g.channel().push(base + (uint32_t)(201 * 65536), 20u << 16, 2, true);
  EXPECT_EQ(g.channel().pending(), 1);
  host::runStepTimer(2000);
  std::vector<Edge> e = stepEdges(2, 5);
  ASSERT_EQ(e.size(), 5u);
  const double want[] = {1100, 1112.5, 1124.5, 1200.5, 1210.5};  // ceilings of the exact half µs
  for (int i = 0; i < 5; i++) {
    EXPECT_DOUBLE_EQ(e[i].us, want[i]) << i;
    EXPECT_EQ(e[i].backward, i >= 3) << i;
  }
  EXPECT_EQ(g.channel().pending(), 0);
  EXPECT_FALSE(host::stepTimerArmed());

  // Taking back: steps at 3000 + 10·j µs, j = 0..9; drop from 3045 µs: 5 go out.
  host::clearPinLog();
  g.channel().push(StepTimer::ticksAt(3000), 20u << 16, 10, false);
  g.channel().push(StepTimer::ticksAt(3200), 20u << 16, 4, false);
  host::runStepTimer(3015);  // 3000 and 3010 are out
  EXPECT_EQ(g.channel().pending(), 12);
  EXPECT_EQ(g.channel().dropFrom(StepTimer::ticksAt(3045)), 9);  // 3050..3090 and the 4 of the next run
  EXPECT_EQ(g.channel().pending(), 3);
  host::runStepTimer(4000);
  e = stepEdges(2, 5);
  ASSERT_EQ(e.size(), 5u);
  EXPECT_DOUBLE_EQ(e.back().us, 3040);
  StepTimer::detach(&g.channel());
}

TEST(StepChannel, StepsAlreadyDueGoAtOnceAndInOrder) {
  host::reset();
  MAXL_StepGenerator g(2, 5, 80.0f);
  g.begin();
  ASSERT_TRUE(StepTimer::attach(&g.channel()));
  host::setMicros(5000);
  host::clearPinLog();
  // a burst planned for 4000 µs (past) and a run from 4990 µs: all late, in order, spaced by the timer
  g.channel().push(StepTimer::ticksAt(4000), 0, 3, false);
  g.channel().push(StepTimer::ticksAt(4990), 10u << 16, 3, false);
  host::runStepTimer(5100);
  std::vector<Edge> e = stepEdges(2, 5);
  ASSERT_EQ(e.size(), 6u);
  for (size_t i = 1; i < e.size(); i++) EXPECT_GE(e[i].us - e[i - 1].us, MAXL_STEP_MIN_TICKS / 2.0) << i;
  EXPECT_GE(e[0].us, 5000);
  StepTimer::detach(&g.channel());
}

// Timer 1 counts 2 per µs in 16 bits: it wraps every 32 768 µs. A run whose
// steps straddle the wrap goes out at its exact times, in order.
TEST(StepChannel, RunAcrossTheTimerWrap) {
  host::reset();
  MAXL_StepGenerator g(2, 5, 80.0f);
  g.begin();
  ASSERT_TRUE(StepTimer::attach(&g.channel()));
  host::setMicros(3 * 32768 + 32700);  // count 65 400, 3 wraps in
  host::clearPinLog();
  // 8 steps every 12.25 µs from 32 740 µs past the last wrap: the count wraps after the third
  g.channel().push(StepTimer::ticksAt(3 * 32768 + 32740), (uint32_t)(24.5 * 65536), 8, false);
  host::runStepTimer(4 * 32768 + 500);
  std::vector<Edge> e = stepEdges(2, 5);
  ASSERT_EQ(e.size(), 8u);
  for (int i = 0; i < 8; i++) {
    double exact = 3 * 32768 + 32740 + 12.25 * i;
    EXPECT_DOUBLE_EQ(e[i].us, std::ceil(exact * 2) / 2) << i;  // never early, at most half a µs late
    EXPECT_FALSE(e[i].backward);
  }
  EXPECT_EQ(g.channel().pending(), 0);
  StepTimer::detach(&g.channel());
}

// What the AVR vector (assembly, step_timer.cpp) relies on without checking:
// a channel is idle exactly when current_ has no steps left (its one test for
// "no run"), and whenever it is busy after an interrupt, the DIR state
// backward_ is current_'s direction (it updates DIR only when a promoted run
// changes it). Random pushes of 1–3 steps in random directions, drops, clears
// and timer runs over two channels; checked after every operation.
TEST(StepChannel, IdleMeansNoStepsInCurrentAndDirFollowsTheRunGoingOut) {
  host::reset();
  MAXL_StepGenerator a(2, 5, 80.0f), b(3, 6, 80.0f, true);
  a.begin();
  b.begin();
  ASSERT_TRUE(StepTimer::attach(&a.channel()));
  ASSERT_TRUE(StepTimer::attach(&b.channel()));
  uint32_t t = 1000, rng = 12345u;
  auto next = [&rng]() { return rng = rng * 1664525u + 1013904223u; };
  host::setMicros(t);
  int queuedReversals = 0;
  for (int op = 0; op < 4000; op++) {
    StepChannel& c = (next() >> 16) & 1 ? a.channel() : b.channel();
    uint32_t pick = (next() >> 16) % 10;
    if (pick < 6) {
      if (c.free()) {
        uint8_t before = c.busy() ? (uint8_t)(c.current_.count & StepChannel::BACKWARD) : 0;
        bool backward = (next() >> 16) & 1;
        uint32_t at = StepTimer::ticksAt(t + (next() >> 16) % 200);
        c.push(at, ((next() >> 16) % 40 + 1) << 16, (uint8_t)((next() >> 16) % 3 + 1), backward);
        if (c.busy() && backward != (before != 0)) queuedReversals++;
      }
    } else if (pick < 9) {
      t += (next() >> 16) % 150;
      host::runStepTimer(t);
    } else if (pick == 9 && (next() >> 16) % 4 == 0) {
      c.clear();
    } else {
      c.dropFrom(StepTimer::ticksAt(t + (next() >> 16) % 100));
    }
    for (StepChannel* ch : {&a.channel(), &b.channel()}) {
      ASSERT_EQ(ch->busy(), (ch->current_.count & StepChannel::MAX_RUN) != 0) << "op " << op;
      if (ch->busy()) ASSERT_EQ(ch->backward_, ch->current_.count & StepChannel::BACKWARD) << "op " << op;
    }
  }
  EXPECT_GT(queuedReversals, 100);  // runs queued against the one going out: DIR changes on promotion
  StepTimer::detach(&a.channel());
  StepTimer::detach(&b.channel());
}

// ---------------------------------------------------------------- window maths

// Windows along exact quadratic paths, planned as MAXL_Stepper does (lag =
// margin, plus the bend c·W²/4 where the path speeds up): every step there,
// none early, the lag within the bend and the margin.
TEST(StepWindow, QuadraticPathsEveryStepNoneEarlyLagBounded) {
  uint32_t rng = 2024;
  auto uniform = [&rng](double a, double b) {
    rng = rng * 1664525u + 1013904223u;
    return a + (b - a) * (rng >> 8) / 16777216.0;
  };
  for (int trial = 0; trial < 400; trial++) {
    double stepsPerMm = uniform(5, 400);
    MAXL_StepGenerator g(2, 5, (float)stepsPerMm);
    double s = 65536.0 / stepsPerMm;
    // p(t) = p0 + v·t + c·t² over 20 ms, units and µs; |v| up to 1 m/s, |a| up to 50 000 mm/s²
    double v0 = uniform(-1, 1) * 65.536 * (trial % 3 == 0 ? 0.01 : 1);
    double c = uniform(-1, 1) * 0.5 * 50000 * 65536e-12;
    double p0 = uniform(-1e6, 1e6);
    double T = 20000;
    // keep it monotonic: stop where the speed would reverse
    if (v0 * c < 0) T = std::min(T, std::fabs(v0 / (2 * c)));
    if (T < 200) continue;
    auto p = [&](double t) { return p0 + v0 * t + c * t * t; };
    bool up = (v0 + c * T) > 0 || (v0 == 0 && c > 0);
    g.reference((int32_t)std::floor(p(0)));
    int32_t n0 = g.steps();
    double emitted = 0;  // steps planned
    std::vector<double> times;
    std::vector<double> spans;  // |Δ| of each step's window
    int w = 1024 >> (trial % 4);
    // as MAXL_Stepper::plan(): a window holds at most MAXL_STEP_WINDOW_STEPS
    // steps (halved down to 128 µs; up to 600 kHz here)
    double fastest = std::max(std::fabs(v0), std::fabs(v0 + 2 * c * T));
    while (w > MAXL_STEP_WINDOW_MIN_US && fastest * w > MAXL_STEP_WINDOW_STEPS * std::floor(s)) w >>= 1;
    ASSERT_LE(fastest * w / s, 126.0) << trial;
    for (double t0 = 0; t0 < T; t0 += w) {
      double t1 = std::min(T, t0 + w);
      int32_t a = (int32_t)std::floor(p(t0)), b = (int32_t)std::floor(p(t1));
      double bend = std::fabs(c) * (t1 - t0) * (t1 - t0) / 4;
      bool speedingUp = c != 0 && ((c > 0) == (b > a));
      int32_t lag = MAXL_STEP_LAG_UNITS + (speedingUp ? (int32_t)std::ceil(bend) + 1 : 0);
      MAXL_StepWindow out;
      g.planWindow((uint16_t)(t1 - t0), a, b, lag, out);
      for (int r = 0; r < out.runs; r++) {
        EXPECT_EQ(out.run[r].backward, !up);
        for (int k = 0; k < out.run[r].count; k++) {
          times.push_back(t0 + (out.run[r].first + (double)k * out.run[r].interval) / 65536.0);
          spans.push_back(std::fabs((double)b - (double)a));
          emitted++;
        }
      }
    }
    // every step the path crosses, by one window's lag at most
    double endPos = p(T);
    int32_t nEnd = (int32_t)std::floor(endPos / s + 0.5);
    int32_t due = std::abs(nEnd - n0);
    ASSERT_LE(std::fabs(emitted - due), 1 + (MAXL_STEP_LAG_UNITS + std::fabs(c) * w * w / 4) / s) << trial << " spm " << stepsPerMm << " v0 " << v0 << " c " << c << " T " << T;
    for (size_t k = 1; k <= times.size(); k++) {
      double threshold = up ? (n0 + (double)k - 0.5) * s : (n0 - (double)k + 0.5) * s;
      // exact crossing of the quadratic
      double lo = 0, hi = T;
      for (int i = 0; i < 80; i++) {
        double mid = 0.5 * (lo + hi);
        if (up ? p(mid) >= threshold : p(mid) < threshold)
          hi = mid;
        else
          lo = mid;
      }
      double lag = times[k - 1] - hi;
      ASSERT_GE(lag, -1e-6) << "trial " << trial << " step " << k;  // never early
      // How far the path has gone past the threshold when the step comes: at
      // most the bend, the margin and a few units (the floors of p0 and p1,
      // the bend's rounding), plus what the time's rounding adds: R is
      // rounded up by < 2^-20 µs per unit, over at most |Δ| units, and the
      // times by 2·2^-16 µs, at the path's speed.
      double te = std::min(times[k - 1], T);
      double behind = up ? p(te) - threshold : threshold - p(te);
      double bendMax = std::fabs(c) * w * w / 4;
      double rounding = std::fabs(v0 + 2 * c * te) * (spans[k - 1] / 1048576.0 + 2.0 / 65536.0);
      ASSERT_LE(behind, bendMax + MAXL_STEP_LAG_UNITS + 3 + rounding) << "trial " << trial << " step " << k;
    }
  }
}

// A lag that shrinks from one window to the next (a window cut short at a
// piece's end has a smaller bend; a speed-up ends) makes no burst run: the
// thresholds in between stay in the window's one run (the ring holds a window
// more), no step is earlier than the path allows, none later than the larger
// lag held it. A jump (p0 steps past the thresholds) is still a burst.
TEST(StepWindow, ShrinkingLagMakesNoBurst) {
  for (int dir = -1; dir <= 1; dir += 2) {
    const double stepsPerMm = 80;
    const double s = 65536.0 / stepsPerMm;  // 819.2 units a step
    MAXL_StepGenerator g(2, 5, (float)stepsPerMm);
    const double v = dir * 0.9 * s / 64.0;  // units/µs: ~14 000 steps/s
    const double p0 = 1000.5 * s;
    auto p = [&](double t) { return p0 + v * t; };
    g.reference((int32_t)std::floor(p(0)));
    const int32_t n0 = g.steps();
    const int32_t bigLag = MAXL_STEP_LAG_UNITS + 400, smallLag = MAXL_STEP_LAG_UNITS;
    std::vector<double> times;
    int bursts = 0;
    const int w = 1024;
    for (int i = 0; i < 60; i++) {
      double t0 = (double)i * w, t1 = t0 + w;
      int32_t lag = i % 2 ? smallLag : bigLag;
      MAXL_StepWindow out;
      g.planWindow((uint16_t)w, (int32_t)std::floor(p(t0)), (int32_t)std::floor(p(t1)), lag, out);
      ASSERT_LE(out.runs, 1) << "window " << i << " dir " << dir;
      for (int r = 0; r < out.runs; r++) {
        if (out.run[r].interval == 0 && out.run[r].count > 1) bursts++;
        for (int k = 0; k < out.run[r].count; k++)
          times.push_back(t0 + (out.run[r].first + (double)k * out.run[r].interval) / 65536.0);
      }
    }
    EXPECT_EQ(bursts, 0);
    ASSERT_GT(times.size(), 800u);
    for (size_t k = 1; k <= times.size(); k++) {
      double threshold = dir > 0 ? (n0 + (double)k - 0.5) * s : (n0 - (double)k + 0.5) * s;
      double crossing = (threshold - p0) / v;  // the exact line's
      ASSERT_GE(times[k - 1], crossing - 1e-6) << "step " << k << " dir " << dir;  // never early
      // behind the path by at most the larger lag and a few units of rounding
      ASSERT_LE((times[k - 1] - crossing) * std::fabs(v), bigLag + 3) << "step " << k << " dir " << dir;
    }
    // a jump of five steps at the next window's start: those go at once
    double t0 = 60.0 * w;
    int32_t jumped = (int32_t)std::floor(p(t0) + dir * 5 * s);
    MAXL_StepWindow out;
    g.planWindow((uint16_t)w, jumped, (int32_t)std::floor(p(t0 + w) + dir * 5 * s), smallLag, out);
    ASSERT_EQ(out.runs, 2) << "dir " << dir;
    EXPECT_EQ(out.run[0].interval, 0u);
    EXPECT_GE(out.run[0].count, 4);
  }
}

// The kept lag where the last window's m1 sits just below a threshold that has a
// fraction (819.2 units a step: every threshold has one): the next window, asked
// a smaller lag, keeps exactly the last one, so its first threshold is not
// already due and it has one run. (The lag from the thresholds' floors came out
// a unit larger than the last, was refused, and the window began with a burst.)
TEST(StepWindow, KeptLagBelowAThresholdWithAFraction) {
  const double stepsPerMm = 80;
  const double s = 65536.0 / stepsPerMm;
  const int32_t bigLag = MAXL_STEP_LAG_UNITS + 400, smallLag = MAXL_STEP_LAG_UNITS;
  const int32_t span = (int32_t)(5.3 * s);  // each window ~5 steps
  int cases = 0;
  for (int dir = -1; dir <= 1; dir += 2) {
    for (int32_t offset = 0; offset < (int32_t)s + 2; offset++) {
      MAXL_StepGenerator g(2, 5, (float)stepsPerMm);
      const int32_t start = (int32_t)std::floor(1000 * s) + dir * offset;
      g.reference(start);
      MAXL_StepWindow a, b;
      g.planWindow(1024, start, start + dir * span, bigLag, a);
      g.planWindow(1024, start + dir * span, start + dir * 2 * span, smallLag, b);
      ASSERT_EQ(b.runs, 1) << "dir " << dir << " offset " << offset;
      cases++;
    }
  }
  EXPECT_EQ(cases, 2 * ((int32_t)s + 2));
}

// ---------------------------------------------------------------- a whole device

namespace {
struct Seg {
  double length;  // mm, signed: the direction of this segment
  msg::TimingSegment timing;
};

// Sends the geometry of `segs` from `from` mm (with p0 when `p0`), and their
// timing from `start` unless `timing` is false; records the exact path.
void sendMove(Rig& rig, const std::vector<Seg>& segs, uint32_t start, double from = 0, bool timing = true,
              uint16_t firstId = 0, bool p0 = true) {
  std::vector<int32_t> origin = {mm(from)};
  std::vector<GeometrySegment> geometry;
  double at = from;
  double t = start;
  for (const Seg& s : segs) {
    geometry.push_back({(float)std::fabs(s.length), {mm(at + s.length)}});
    rig.path.pieces.push_back({s.timing, t, (double)mm(at), (double)mm(at + s.length)});
    at += s.length;
    t += durationOf(s.timing);
  }
  for (size_t first = 0; first < geometry.size(); first += 6) {
    std::vector<GeometrySegment> part(geometry.begin() + first, geometry.begin() + std::min(geometry.size(), first + 6));
    rig.send(rig.h.author.geometry((uint16_t)(firstId + first), first == 0 && p0 ? &origin : nullptr, part, 1));
  }
  if (!timing) return;
  for (size_t first = 0; first < segs.size(); first += 4) {
    std::vector<msg::TimingSegment> part;
    for (size_t i = first; i < std::min(segs.size(), first + 4); i++) part.push_back(segs[i].timing);
    rig.send(rig.h.author.timing((uint16_t)(firstId + first), 10000.0f, first == 0 ? &start : nullptr, part));
  }
}

// 500 mm/s (40 000 steps/s at 80 steps/mm): ramps at 10 000 mm/s² (12.5 mm) and `cruise` segments of 10 mm.
std::vector<Seg> fortyKilohertz(int cruise, double sign = 1) {
  std::vector<Seg> segs = {{12.5 * sign, trapezoid(12.5, 0, 500, 500, 10000)}};
  for (int i = 0; i < cruise; i++) segs.push_back({10 * sign, trapezoid(10, 500, 500, 500, 10000)});
  segs.push_back({12.5 * sign, trapezoid(12.5, 500, 500, 0, 10000)});
  return segs;
}

const double S80 = 65536.0 / 80.0;
// The design's lag bound in units: bend <= s/2^MAXL_STEP_BEND_SHIFT, the margin, and the
// fixed-point path's own error (a few units over these short segments).
const double SLACK = S80 / (1 << MAXL_STEP_BEND_SHIFT) + MAXL_STEP_LAG_UNITS + 12;

int32_t stepOf(int32_t units) { return (int32_t)std::floor(units / S80 + 0.5); }

// The step a move of `segs` from 0 ends at (65 mm, 5 200 steps, for fortyKilohertz(4)).
int32_t stepsOf(const std::vector<Seg>& segs) {
  double at = 0;
  for (const Seg& s : segs) at += s.length;
  return stepOf(mm(at));
}

// loop() every `period` µs, but for `stall` µs every `every` µs
std::function<uint32_t(uint32_t)> cadence(uint32_t period, uint32_t stall = 0, uint32_t every = 0) {
  return [=](uint32_t now) { return every && (now / period) % (every / period) == 0 ? now + stall : now + period; };
}
}  // namespace

TEST(TimedStepper, FortyKilohertzEveryStepOnTime) {
  Rig rig(true);
  uint32_t start = rig.now + 20000;
  sendMove(rig, fortyKilohertz(4), start);
  const int32_t total = stepsOf(fortyKilohertz(4));
  ASSERT_EQ(total, 5200);
  host::clearPinLog();
  rig.runUntil((uint32_t)rig.path.end() + 5000, cadence(50));
  Verdict v = judge(rig.path, stepEdges(2, 5), S80, 0, total, SLACK);
  EXPECT_EQ(v.got, total);
  EXPECT_EQ(v.early, 0);
  EXPECT_EQ(v.late, 0);
  EXPECT_EQ(v.tooLaggy, 0) << "max lag " << v.maxLagUs << " µs";
  EXPECT_GE(v.minLagUs, 0.0);
  EXPECT_EQ(rig.stepper.steps(), total);
  EXPECT_EQ(rig.stepper.generator().channel().pending(), 0);
}

// A dwell between two 40 kHz moves (as a plotter's pen drop): to rest, 30 ms
// holding (a segment of length 0, one phase at alpha 0), then on from rest.
// Every step on time on both sides, and none while it holds.
TEST(TimedStepper, DwellHoldsBetweenMovesEveryStepOnTime) {
  Rig rig(true);
  msg::TimingSegment hold{};
  hold.shape = phase::CRUISE;
  hold.phaseCount = 1;
  hold.durations[0] = 30000;
  std::vector<Seg> segs = {{12.5, trapezoid(12.5, 0, 500, 500, 10000)}, {12.5, trapezoid(12.5, 500, 500, 0, 10000)}, {0.0, hold},
                           {12.5, trapezoid(12.5, 0, 500, 500, 10000)}, {12.5, trapezoid(12.5, 500, 500, 0, 10000)}};
  uint32_t start = rig.now + 20000;
  sendMove(rig, segs, start);
  const int32_t total = stepsOf(segs);
  ASSERT_EQ(total, 4000);
  host::clearPinLog();
  rig.runUntil((uint32_t)rig.path.end() + 5000, cadence(50));
  std::vector<Edge> edges = stepEdges(2, 5);
  Verdict v = judge(rig.path, edges, S80, 0, total, SLACK);
  EXPECT_EQ(v.got, total);
  EXPECT_EQ(v.early, 0);
  EXPECT_EQ(v.late, 0);
  EXPECT_EQ(v.tooLaggy, 0) << "max lag " << v.maxLagUs << " µs";
  const double holdStart = start + durationOf(segs[0].timing) + durationOf(segs[1].timing);
  for (const Edge& e : edges) EXPECT_FALSE(e.us > holdStart + 1 && e.us < holdStart + 30000) << e.us;
  EXPECT_EQ(rig.stepper.steps(), total);
}

// loop() stalls 2 ms every 5 ms (a STATUS, a TIMING's float maths, a slow
// callback): the timer keeps the steps on time. The same stalls make the
// polled stepper late, so the test can tell.
TEST(TimedStepper, LoopStallsDoNotDelaySteps) {
  for (bool timed : {true, false}) {
    Rig rig(timed);
    uint32_t start = rig.now + 20000;
    sendMove(rig, fortyKilohertz(4), start);
    host::clearPinLog();
    rig.runUntil((uint32_t)rig.path.end() + 5000, cadence(50, 2000, 5000));
    Verdict v = judge(rig.path, stepEdges(2, 5), S80, 0, 5200, SLACK);
    EXPECT_EQ(v.got, 5200);
    if (timed) {
      EXPECT_EQ(v.early, 0);
      EXPECT_EQ(v.late, 0);
      EXPECT_EQ(v.tooLaggy, 0) << "max lag " << v.maxLagUs << " µs";
    } else {
      EXPECT_GT(v.late, 100) << "the polled stepper should be late through the stalls";
    }
  }
}

// The timing arrives while the machine moves, each segment's a few ms before
// the one before it ends (as the author's streamer sends it), with loop()
// every 100 µs: every step on time, as when all timing came first.
TEST(TimedStepper, TimingStreamedDuringTheMove) {
  Rig rig(true);
  std::vector<Seg> segs = fortyKilohertz(8);
  uint32_t start = rig.now + 20000;
  sendMove(rig, segs, start, 0, false);
  host::clearPinLog();
  double t = start;
  for (size_t i = 0; i < segs.size(); i++) {
    // segment i's timing goes 4 ms before it starts (the first: 10 ms before)
    uint32_t sendAt = (uint32_t)(t - (i == 0 ? 10000 : 4000));
    rig.runUntil(sendAt, cadence(100));
    rig.send(rig.h.author.timing((uint16_t)i, 10000.0f, i == 0 ? &start : nullptr, {segs[i].timing}));
    for (const Answer& a : rig.h.answers()) EXPECT_EQ(a.reason, 0) << i;
    t += durationOf(segs[i].timing);
  }
  rig.runUntil((uint32_t)rig.path.end() + 5000, cadence(100));
  ASSERT_EQ(stepsOf(segs), 8400);
  Verdict v = judge(rig.path, stepEdges(2, 5), S80, 0, 8400, SLACK);
  EXPECT_EQ(v.got, 8400);
  EXPECT_EQ(v.early, 0);
  EXPECT_EQ(v.late, 0);
  EXPECT_EQ(v.tooLaggy, 0) << "max lag " << v.maxLagUs << " µs";
}

// The same move across the device clock's u32 wrap (71.6 min): every step on time.
TEST(TimedStepper, AcrossTheClockWrap) {
  Rig rig(true, 0xFFFFFFFFu - 60000);
  uint32_t start = rig.now + 20000;
  std::vector<Seg> segs = fortyKilohertz(4);
  sendMove(rig, segs, start);
  ASSERT_GT(rig.path.end(), 4294967296.0 + 50000);  // the wrap is mid-move
  host::clearPinLog();
  rig.runUntil(Rig::clock(rig.path.end() + 5000), cadence(50));
  Verdict v = judge(rig.path, stepEdges(2, 5), S80, 0, stepsOf(segs), SLACK);
  EXPECT_EQ(v.got, stepsOf(segs));
  EXPECT_EQ(v.early, 0);
  EXPECT_EQ(v.late, 0);
  EXPECT_EQ(v.tooLaggy, 0) << "max lag " << v.maxLagUs << " µs";
  EXPECT_EQ(rig.stepper.steps(), stepsOf(segs));
}

// 200 steps/mm at 500 mm/s: 100 kHz, 205 steps in a 2 ms window, more than
// a window may hold (MAXL_STEP_WINDOW_STEPS): the windows are split, and
// every step is still on time (no catch-up bursts).
TEST(TimedStepper, FastMotorWindowsAreSplit) {
  Rig rig(true, 0, 200.0f);
  const double s = 65536.0 / 200.0;
  uint32_t start = rig.now + 20000;
  std::vector<Seg> segs = fortyKilohertz(2);
  sendMove(rig, segs, start);
  host::clearPinLog();
  rig.runUntil(Rig::clock(rig.path.end() + 5000), cadence(50));
  int32_t total = (int32_t)std::floor(mm(45.0) / s + 0.5);
  ASSERT_EQ(total, 9000);
  Verdict v = judge(rig.path, stepEdges(2, 5), s, 0, total, s / (1 << MAXL_STEP_BEND_SHIFT) + MAXL_STEP_LAG_UNITS + 12);
  EXPECT_EQ(v.got, total);
  EXPECT_EQ(v.early, 0);
  EXPECT_EQ(v.late, 0);
  EXPECT_EQ(v.tooLaggy, 0) << "max lag " << v.maxLagUs << " µs";
  EXPECT_EQ(rig.stepper.steps(), total);
}

// Out and back, with a pause between: DIR follows, every step both ways.
TEST(TimedStepper, OutAndBack) {
  Rig rig(true);
  uint32_t start = rig.now + 20000;
  std::vector<Seg> out = {{20, trapezoid(20, 0, 200, 0, 4000)}};
  sendMove(rig, out, start);
  host::clearPinLog();
  rig.runUntil((uint32_t)rig.path.end() + 3000, cadence(70));
  Verdict v = judge(rig.path, stepEdges(2, 5), S80, 0, 1600, SLACK);
  EXPECT_EQ(v.got, 1600);
  EXPECT_EQ(v.early + v.late + v.tooLaggy, 0);
  // back, from where it is (ids go on)
  Path forth = rig.path;
  rig.path.pieces.clear();
  uint32_t back = rig.now + 10000;
  sendMove(rig, {{-20, trapezoid(20, 0, 300, 0, 6000)}}, back, 20, true, 1, false);
  host::clearPinLog();
  rig.runUntil((uint32_t)rig.path.end() + 3000, cadence(70));
  v = judge(rig.path, stepEdges(2, 5), S80, 1600, -1600, SLACK);
  EXPECT_EQ(v.got, 1600);
  EXPECT_EQ(v.early + v.late + v.tooLaggy, 0);
  EXPECT_EQ(rig.stepper.steps(), 0);
}

// HALT mode 0 mid-cruise: the steps planned past it are taken back; the
// motor ends at the step of the position the device stopped at.
TEST(TimedStepper, HaltNowTakesBackWhatWasPlanned) {
  Rig rig(true);
  uint32_t start = rig.now + 20000;
  sendMove(rig, fortyKilohertz(4), start);
  host::clearPinLog();
  rig.runUntil(start + 70000, cadence(50));  // mid-cruise
  EXPECT_GT(rig.stepper.generator().channel().pending(), 40);  // ms of steps planned ahead
  rig.send(rig.h.author.halt(0, 0));
  uint32_t haltedAt = rig.now;
  rig.runUntil(rig.now + 20000, cadence(50));
  int32_t stop = stepOf(rig.h.device->positionUnits(0));
  EXPECT_EQ(rig.stepper.steps(), stop);
  std::vector<Edge> e = stepEdges(2, 5);
  EXPECT_EQ((int32_t)e.size(), stop);
  for (const Edge& x : e) EXPECT_FALSE(x.backward);
  EXPECT_LT(e.back().us, haltedAt + 100);
  EXPECT_EQ(rig.stepper.generator().channel().pending(), 0);
}

// HALT mode 1 at a time inside what is already planned (1 ms ahead, the
// plan reaches 3 ms): the steps past it are taken back and the motor follows
// the braking from there, never backwards, and ends where the device stops.
TEST(TimedStepper, HaltBrakeAtInsideThePlan) {
  Rig rig(true);
  uint32_t start = rig.now + 20000;
  std::vector<Seg> segs = fortyKilohertz(4);
  sendMove(rig, segs, start);
  host::clearPinLog();
  rig.runUntil(start + 70000, cadence(50));
  uint32_t at = rig.now + 1000;
  rig.send(rig.h.author.halt(1, at));
  for (const Answer& a : rig.h.answers()) EXPECT_EQ(a.reason, 0);
  int worst = 0;
  while (rig.h.device->state() != state::STOPPED && rig.h.device->state() != state::IDLE && timeBefore(rig.now, start + 400000)) {
    rig.runUntil(rig.now + 50, cadence(50));
    worst = std::max(worst, std::abs(rig.stepper.steps() - stepOf(rig.h.device->positionUnits(0))));
  }
  rig.runUntil(rig.now + 5000, cadence(50));
  EXPECT_LE(worst, 2);
  EXPECT_EQ(rig.stepper.steps(), stepOf(rig.h.device->positionUnits(0)));
  std::vector<Edge> e = stepEdges(2, 5);
  EXPECT_EQ((int32_t)e.size(), rig.stepper.steps());
  for (const Edge& x : e) EXPECT_FALSE(x.backward);
  // up to `at` the steps are those of the unbraked path
  Path before = rig.path;
  int32_t atStep = stepOf((int32_t)before.at(at) - MAXL_STEP_LAG_UNITS) - 1;
  std::vector<Edge> head(e.begin(), e.begin() + std::max(0, atStep));
  Verdict v = judge(before, head, S80, 0, atStep, SLACK);
  EXPECT_EQ(v.early + v.late + v.tooLaggy, 0);
}

// The timing runs out while moving: the device brakes along the provisional
// geometry (protocol §6) and the motor follows, a loop or so behind at the
// brake's start (it cannot be planned before the device decides), never
// backwards, to the step the device stops at.
TEST(TimedStepper, StarvedBrakingIsFollowed) {
  Rig rig(true);
  uint32_t start = rig.now + 20000;
  std::vector<Seg> segs = fortyKilohertz(6);
  sendMove(rig, segs, start, 0, false);
  // timing for the ramp and 2 cruise segments only
  std::vector<msg::TimingSegment> part = {segs[0].timing, segs[1].timing, segs[2].timing};
  rig.send(rig.h.author.timing(0, 10000.0f, &start, part));
  host::clearPinLog();
  int worst = 0;
  while (rig.h.device->state() != state::STOPPED && timeBefore(rig.now, start + 400000)) {
    rig.runUntil(rig.now + 50, cadence(50));
    worst = std::max(worst, std::abs(rig.stepper.steps() - stepOf(rig.h.device->positionUnits(0))));
  }
  EXPECT_EQ(rig.h.device->state(), state::STOPPED);
  rig.runUntil(rig.now + 5000, cadence(50));
  EXPECT_LE(worst, 3);
  EXPECT_EQ(rig.stepper.steps(), stepOf(rig.h.device->positionUnits(0)));
  std::vector<Edge> e = stepEdges(2, 5);
  EXPECT_EQ((int32_t)e.size(), rig.stepper.steps());
  for (const Edge& x : e) EXPECT_FALSE(x.backward);
}

// A new session mid-move: nothing more goes out, and the count is the motor's.
TEST(TimedStepper, NewSessionDropsThePlan) {
  Rig rig(true);
  uint32_t start = rig.now + 20000;
  sendMove(rig, fortyKilohertz(4), start);
  host::clearPinLog();
  rig.runUntil(start + 60000, cadence(50));
  rig.send(rig.h.author.helloRequest());
  uint32_t at = rig.now;
  rig.runUntil(rig.now + 20000, cadence(50));
  std::vector<Edge> e = stepEdges(2, 5);
  EXPECT_LT(e.back().us, at + 50);
  EXPECT_EQ((int32_t)e.size(), rig.stepper.steps());
  EXPECT_EQ(rig.stepper.generator().channel().pending(), 0);
  EXPECT_FALSE(host::stepTimerArmed());
}

// ---------------------------------------------------------------- one grid, several steppers

namespace {

// Two steppers on one device, on slots 0 and 1 (80 steps/mm, STEP 2 and 3, DIR
// 5 and 6), both on the step timer, given a CoreXY line at 30° to x: motor
// a = x + y moves 1.366·s, motor b = x − y 0.366·s for s along the line.
struct PairRig {
  MAXL_Stepper a{"a", 2, 5, 80.0f};
  MAXL_Stepper b{"b", 3, 6, 80.0f};
  Harness h;
  uint32_t now = 0;
  const double th = 30.0 * M_PI / 180.0;
  const double scale[2] = {std::cos(th) + std::sin(th), std::cos(th) - std::sin(th)};

  PairRig() {
    EXPECT_TRUE(a.useStepTimer(true));
    EXPECT_TRUE(b.useStepTimer(true));
    host::setMicros(0);
    h.open({{0, kind::POSITION, 0}, {1, kind::POSITION, 1}});
  }
  void send(const Bytes& frame) {
    host::runStepTimer(now);
    host::pushRx(frame.data(), frame.size());
    while (host::rxPending()) {
      now += 20;
      host::runStepTimer(now);
      h.loop();
    }
  }
  // Sends `segs` (signed mm along the line, their timing) from 20 ms from now, the
  // first four in one GEOMETRY and TIMING and the rest in another; returns each
  // motor's exact path.
  std::array<Path, 2> sendLine(const std::vector<std::pair<double, msg::TimingSegment>>& segs) {
    uint32_t start = now + 20000;
    std::array<Path, 2> path;
    std::vector<GeometrySegment> geometry;
    double along = 0, t = start;
    for (const auto& s : segs) {
      GeometrySegment g;
      g.length = (float)std::fabs(s.first);
      for (int m = 0; m < 2; m++) {
        path[m].pieces.push_back({s.second, t, (double)mm(along * scale[m]), (double)mm((along + s.first) * scale[m])});
        g.p1.push_back(mm((along + s.first) * scale[m]));
      }
      geometry.push_back(g);
      along += s.first;
      t += durationOf(s.second);
    }
    std::vector<int32_t> origin = {0, 0};
    send(h.author.geometry(0, &origin, std::vector<GeometrySegment>(geometry.begin(), geometry.begin() + 4), 2));
    send(h.author.geometry(4, nullptr, std::vector<GeometrySegment>(geometry.begin() + 4, geometry.end()), 2));
    std::vector<msg::TimingSegment> timing;
    for (const auto& s : segs) timing.push_back(s.second);
    send(h.author.timing(0, 10000.0f, &start, std::vector<msg::TimingSegment>(timing.begin(), timing.begin() + 4)));
    send(h.author.timing(4, 10000.0f, nullptr, std::vector<msg::TimingSegment>(timing.begin() + 4, timing.end())));
    return path;
  }
};

}  // namespace

// Two steppers on one device, on slots 0 and 1, planned on the device's one
// window grid (step_planner.h) and stepped from one interrupt: a CoreXY line
// at 30° to x at 300 mm/s (motor a = x + y at 1.366·v, motor b = x − y at
// 0.366·v: 32 800 and 8 780 steps/s), and back. Every step of each motor is
// there, none early, none later than its own step period, and each within the
// design's lag.
TEST(TimedStepperGrid, TwoSteppersAtUnequalRatesEveryStepOnTime) {
  PairRig rig;
  // out 60 mm along the line and back: ramps at 10 000 mm/s², 300 mm/s cruise
  const double v = 300, acc = 10000, ramp = v * v / (2 * acc);  // 4.5 mm
  std::array<Path, 2> path = rig.sendLine({{ramp, trapezoid(ramp, 0, v, v, acc)},
                                           {60 - 2 * ramp, trapezoid(60 - 2 * ramp, v, v, v, acc)},
                                           {ramp, trapezoid(ramp, v, v, 0, acc)},
                                           {-ramp, trapezoid(ramp, 0, v, v, acc)},
                                           {-(60 - 2 * ramp), trapezoid(60 - 2 * ramp, v, v, v, acc)},
                                           {-ramp, trapezoid(ramp, v, v, 0, acc)}});
  host::clearPinLog();
  uint32_t end = (uint32_t)path[0].end() + 5000;
  while (timeBefore(rig.now, end)) {
    rig.now += 50;
    host::runStepTimer(rig.now);
    rig.h.loop();
  }
  const uint8_t stepPins[2] = {2, 3}, dirPins[2] = {5, 6};
  for (int m = 0; m < 2; m++) {
    std::vector<Edge> edges = stepEdges(stepPins[m], dirPins[m]);
    // out: steps up to the far end, then back down to 0
    int32_t far = stepOf(mm(60 * rig.scale[m]));
    std::vector<Edge> out(edges.begin(), edges.begin() + std::min<size_t>(edges.size(), (size_t)far));
    Path outPath = path[m], backPath = path[m];
    outPath.pieces.resize(3);
    backPath.pieces.erase(backPath.pieces.begin(), backPath.pieces.begin() + 3);
    Verdict vo = judge(outPath, out, S80, 0, far, SLACK);
    EXPECT_EQ(vo.got, far) << "motor " << m;
    EXPECT_EQ(vo.early, 0) << "motor " << m;
    EXPECT_EQ(vo.late, 0) << "motor " << m << " max lag " << vo.maxLagUs;
    EXPECT_EQ(vo.tooLaggy, 0) << "motor " << m << " max lag " << vo.maxLagUs;
    std::vector<Edge> back(edges.begin() + std::min<size_t>(edges.size(), (size_t)far), edges.end());
    Verdict vb = judge(backPath, back, S80, far, -far, SLACK);
    EXPECT_EQ(vb.got, far) << "motor " << m;
    EXPECT_EQ(vb.early, 0) << "motor " << m;
    EXPECT_EQ(vb.late, 0) << "motor " << m << " max lag " << vb.maxLagUs;
    EXPECT_EQ(vb.tooLaggy, 0) << "motor " << m << " max lag " << vb.maxLagUs;
  }
  EXPECT_EQ(rig.a.steps(), 0);
  EXPECT_EQ(rig.b.steps(), 0);
}

// The planner reuses gridTooMany(t1)'s position as the window's end where
// gridSized(t1) says Motion::lookAt would compute the same (windowEnd in
// step_planner.cpp). Checked at every loop of a two-stepper move (ramps,
// cruise, segment ends, out and back): for ends t1 across the walk's current
// piece (its start, steps of 97 µs, the piece's end and a unit either side),
// wherever gridSized(t1) holds, lookAt on a copy of the walk gives exactly
// gridTooMany's position and does not move the copy.
struct MAXL_StepperGridCheck {
  static uint16_t windowFor(const MAXL_Stepper& s, int32_t c) { return s.windowFor(c); }
  int sized = 0, notSized = 0, mismatched = 0, moved = 0;
  void at(const Motion& motion, const MAXL_Stepper& s) {
    if (!s.synced_ || s.look_.state == Lookahead::REST) return;
    std::vector<uint32_t> ends = {s.look_.pieceEnd, s.look_.pieceEnd - 1, s.look_.pieceEnd + 1};
    for (uint32_t t = s.look_.chunkStart; timeBefore(t, s.look_.pieceEnd); t += 97) ends.push_back(t);
    for (uint32_t t1 : ends) {
      if (!s.gridSized(t1)) {
        notSized++;
        continue;
      }
      sized++;
      Lookahead copy = s.look_;
      int32_t fromLookAt = motion.lookAt(copy, s.slot(), t1);
      int32_t fromTooMany = 0;
      s.gridTooMany(t1, fromTooMany);
      if (fromLookAt != fromTooMany) mismatched++;
      if (copy.chunkStart != s.look_.chunkStart || copy.track.P != s.look_.track.P || copy.track.B != s.look_.track.B)
        moved++;
    }
  }
};

TEST(TimedStepperGrid, WindowEndReusesTheSizingPositionOnlyWhereLookAtAgrees) {
  PairRig rig;
  // 30° to x (unequal rates), short segments so that pieces and segments end often
  const double v = 300, acc = 10000, ramp = v * v / (2 * acc);  // 4.5 mm
  std::array<Path, 2> path = rig.sendLine(
      {{ramp, trapezoid(ramp, 0, v, v, acc)}, {3, trapezoid(3, v, v, v, acc)}, {3, trapezoid(3, v, v, v, acc)},
       {ramp, trapezoid(ramp, v, v, 0, acc)}, {-ramp, trapezoid(ramp, 0, v, v, acc)}, {-3, trapezoid(3, v, v, v, acc)},
       {-3, trapezoid(3, v, v, v, acc)},      {-ramp, trapezoid(ramp, v, v, 0, acc)}});
  const double end = path[0].end();
  MAXL_StepperGridCheck check;
  while (timeBefore(rig.now, (uint32_t)end + 5000)) {
    rig.now += 50;
    host::runStepTimer(rig.now);
    rig.h.loop();
    check.at(rig.h.device->motion(), rig.a);
    check.at(rig.h.device->motion(), rig.b);
  }
  EXPECT_GT(check.sized, 10000);
  EXPECT_GT(check.notSized, 100);  // the pieces' ends of segments, and past them
  EXPECT_EQ(check.mismatched, 0);
  EXPECT_EQ(check.moved, 0);
  EXPECT_EQ(rig.a.steps(), 0);
  EXPECT_EQ(rig.b.steps(), 0);
}

// The bend criterion (stepper.h, config.h): windowFor(c) is the longest power
// of two W from MAXL_STEP_WINDOW_MAX_US down to MAXL_STEP_WINDOW_MIN_US whose
// bend |C|·W²/2^34 is at most s/2^MAXL_STEP_BEND_SHIFT, i.e. |C|·W² <= s·2^(34 − b)
// exactly (128-bit here), or the shortest where none is. Checked at every
// bound and ±1 around it, at random |C| and at INT32_MIN, both signs, for
// step sizes from 1/256 mm down to 1/3200 mm.
TEST(TimedStepperGrid, WindowIsTheLongestWhoseBendIsWithinTheBound) {
  host::reset();
  uint32_t seed = 12345;
  auto next = [&seed]() { return seed = seed * 1664525u + 1013904223u; };
  int checked = 0, atMax = 0, shorter = 0;
  for (float stepsPerMm : {1.0f, 5.0f, 80.0f, 200.0f, 256.0f, 3200.0f}) {
    MAXL_Stepper stepper("bend", 2, 5, stepsPerMm);
    const uint64_t units = (uint64_t)(uint32_t)stepper.generator().unitsPerStep();
    auto expected = [&](int32_t c) {
      unsigned __int128 a = c < 0 ? (unsigned __int128)(-(int64_t)c) : (unsigned __int128)c;
      for (uint32_t w = MAXL_STEP_WINDOW_MAX_US; w >= MAXL_STEP_WINDOW_MIN_US; w >>= 1)
        if (a * w * w <= ((unsigned __int128)units << (34 - MAXL_STEP_BEND_SHIFT))) return (uint16_t)w;
      return (uint16_t)MAXL_STEP_WINDOW_MIN_US;
    };
    std::vector<int32_t> cs = {0, 1, -1, INT32_MAX, INT32_MIN};
    for (uint32_t w = MAXL_STEP_WINDOW_MAX_US; w >= MAXL_STEP_WINDOW_MIN_US; w >>= 1) {
      uint64_t bound = (units << (34 - MAXL_STEP_BEND_SHIFT)) / ((uint64_t)w * w);  // the largest |C| for w
      for (int64_t d = -1; d <= 1; d++) {
        int64_t c = (int64_t)bound + d;
        if (c >= 0 && c <= INT32_MAX) {
          cs.push_back((int32_t)c);
          cs.push_back((int32_t)-c);
        }
      }
    }
    for (int i = 0; i < 20000; i++) cs.push_back((int32_t)(next() >> (next() % 31)));
    for (int32_t c : cs) {
      uint16_t got = MAXL_StepperGridCheck::windowFor(stepper, c);
      ASSERT_EQ(got, expected(c)) << "c " << c << " at " << stepsPerMm << " steps/mm";
      checked++;
      if (got == MAXL_STEP_WINDOW_MAX_US) atMax++;
      else shorter++;
    }
  }
  EXPECT_GT(checked, 120000);
  EXPECT_GT(atMax, 1000);
  EXPECT_GT(shorter, 1000);
}
