// A position reader that drives a stepper driver directly (step/dir pins),
// from the integer position: no float work per evaluation.
//
//   MAXL_Stepper stepper("stepper", 2 /*step*/, 5 /*dir*/, 80.0f /*steps/mm*/);
//
// It is the efficient form of the paper's Listing 3 (a
// MAXL_TrackPositionLinear whose callback counts steps), with every due step
// emitted (see step_generator.h).
//
// Where the board has a step timer (MAXL_STEP_TIMER: 16 MHz AVRs, Timer 1),
// steps come from its interrupt at their own times (step_timer.h), planned
// by loop() a few ms ahead:
//
//   loop():    the device's step planner (step_planner.h) plans one window
//              grid for all its timed steppers: from where the last plan
//              ended (t0), the next window of the path, up to the next
//              multiple of its length W (a power of two, 128..2048 µs, the
//              shortest any of the steppers needs where the path bends), or
//              to the end of its phase, segment or brake piece, whichever
//              comes first; each stepper evaluates its slot at the window's
//              end with the device's own fixed-point path (Motion's
//              Lookahead, bit for bit what Motion will compute) and turns
//              the window into step times (MAXL_StepWindow) for the timer.
//              Repeat until the plan reaches MAXL_STEP_LEAD_US past the
//              device clock, or what is certain ends (no timing yet,
//              braking, a pending HALT).
//   interrupt: emits every due step of every stepper, in one pass.
//
// Inside a window the steps follow a straight line between the exact
// positions at its ends. A piece of the path is a quadratic p(t), with half
// acceleration c (units/µs²). Where it slows down (c against the motion) the
// chord lies behind the path, so steps from it come late, never early. Where
// it speeds up the chord lies ahead by up to c·W²/4 (at the middle), so the
// line is moved back by exactly that: it is then the tangent at the window's
// middle (same slope (p1 − p0)/W = v + c·W, touching at W/2), and a convex
// path is never below its tangent. Either way every step lags the exact path
// by at most c·W²/4 plus MAXL_STEP_LAG_UNITS (which covers the fixed-point
// path's own error), i.e. by that distance over the speed in time: W is
// halved until c·W²/4 is at most s/2^MAXL_STEP_BEND_SHIFT (s/2 by default,
// config.h), so the lag stays under half a step period plus the margin, at
// any acceleration the fixed-point path allows down to W = 128 µs.
//
// Without a timer (host tests by default, wasm) it steps from loop(): every
// step due at each evaluation.
#ifndef MAXL_READERS_STEPPER_H
#define MAXL_READERS_STEPPER_H

#include <stdint.h>

#include "maxl/motion/motion.h"
#include "maxl/readers/step_generator.h"
#include "maxl/readers/tracks.h"

class MAXL_Stepper : public MAXL_TrackPositionLinear {
 public:
  MAXL_Stepper(const char* name, uint8_t stepPin, uint8_t dirPin, float stepsPerUnit, bool invertDirection = false);
#if MAXL_STEP_TIMER && !defined(__AVR__)
  // Leaves the step timer and the planner (a test's stepper on the stack; a
  // sketch's static steppers live as long as the board runs).
  ~MAXL_Stepper();
#endif

  MAXL_StepGenerator& generator() { return generator_; }
  // The motor's step count: steps emitted so far.
  int32_t steps() const;

  // Steps from the step timer's interrupt (true) or from loop() (false).
  // Asks for one; returns what it got (false without a timer, with invalid
  // pins, or when MAXL_STEP_CHANNELS steppers already use it). Change it only
  // while not subscribed. The default is MAXL_STEP_TIMER_DEFAULT. Built with
  // MAXL_STEPPER_POLLING 0 it always asks for the timer, and a stepper that
  // does not get it (invalid pins, too many steppers) does not step.
  bool useStepTimer(bool on);
  bool usesStepTimer() const { return timed_; }

 protected:
  void onBegin();
  void onPosition(int32_t units, bool first);
  void onTick(MAXL_Device& device);
  void onUnsubscribe();

 private:
  MAXL_StepGenerator generator_;
  bool behind_ : 1;
  bool timed_ : 1;
#if MAXL_STEP_TIMER
  friend class MAXL_StepPlanner;
  friend struct MAXL_StepperGridCheck;  // the host test of gridSized (firmware/test/step_timing_test.cpp)
  bool wantTimer_ : 1;
  bool synced_ : 1;  // look_ and plannedUnits_ follow the planner's grid
  maxl_fw::Lookahead look_;
  int32_t plannedUnits_;  // the position where the plan ends
  // ---- this stepper's part of the planner's grid (step_planner.cpp)
  // Starts the walk where Motion is, first taking back the steps planned
  // from `from` on when `drop`.
  void gridRestart(const maxl_fw::Motion& motion, uint32_t from, bool drop);
  // Walks on to `t` (where the grid starts) and takes the position there.
  void gridJoin(const maxl_fw::Motion& motion, uint32_t t);
  // The longest window this stepper's slot allows for the bend (windowFor).
  uint16_t gridWindow(const maxl_fw::Motion& motion) const;
  // Whether a window ending at t would hold more than MAXL_STEP_WINDOW_STEPS
  // steps; `p` gets the position at t it computed (unsnapped, for gridEnd).
  bool gridTooMany(uint32_t t, int32_t& p) const;
  // The position at the window's end t1 (the walk moves on to it).
  int32_t gridEnd(const maxl_fw::Motion& motion, uint32_t t1);
  // Whether gridTooMany(t1)'s position is what gridEnd(t1) would return:
  // Motion::lookAt computes exactly gridTooMany's sum on the walk's own track
  // when the walk runs (not at rest: a rest position), t1 is not the piece's
  // end (where a segment's end snaps to its p1) and no chunk is crossed
  // (t1 − chunkStart < 2^16 µs, which also rules out t1 before chunkStart,
  // which lookAt would clamp); the walk then does not move.
  bool gridSized(uint32_t t1) const {
    return look_.state != maxl_fw::Lookahead::REST && t1 != look_.pieceEnd && t1 - look_.chunkStart < 65536ul;
  }
  // The window [t0, t1] to p1 becomes step times.
  void gridPlan(const maxl_fw::Motion& motion, uint32_t t0, uint32_t t1, int32_t p1, uint32_t now);
  // The steps of one window [t0, t1] from p0 to p1 on a piece of half acceleration c.
  void schedule(uint32_t t0, uint32_t t1, int32_t p0, int32_t p1, int32_t curvature, uint32_t now);
  // Takes back every planned step from device time `from` on (a HALT, a resync).
  void dropFrom(uint32_t from);
  void tookBack(int16_t dropped);
  uint16_t windowFor(int32_t curvature) const;
  bool tooManySteps(int32_t delta) const;
  void stopTimed();
#endif
};

#endif
