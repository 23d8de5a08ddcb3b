// Turns a position track into step and direction pulses.
//
// The motor is at step n when the position p (units of 2^-16 mm) is within
// half a step of n·s, s = 65536 / stepsPerUnit units per step:
//   n = floor(p/s + 1/2), i.e. (n − 1/2)·s <= p < (n + 1/2)·s.
// So one step up is due when p reaches (n + 1/2)·s, one down when p falls
// below (n − 1/2)·s. The upper threshold is kept exactly, as whole units plus
// a 16-bit fraction (s is too: sWhole + sFrac/2^16), and both thresholds are
// compared through their ceilings in whole units, since p is whole:
// p >= x  <=>  p >= ceil(x), and p < x  <=>  p < ceil(x). Then "is a step
// due?" is two 32-bit compares, a step moves the thresholds with 32-bit
// additions, and an evaluation that moved p by k steps emits all k (the
// paper's prototype emitted at most one per call, capping the step rate at
// the loop rate).
//
// Two ways to use it:
//   moveTo(p)       polled: emits every step due now, from loop() (host, wasm,
//                   and boards without a step timer)
//   planWindow(...) timed: turns a window of the path into step times for the
//                   step timer's interrupt (step_timer.h, MAXL_Stepper)
#ifndef MAXL_READERS_STEP_GENERATOR_H
#define MAXL_READERS_STEP_GENERATOR_H

#include <stdint.h>

#include "maxl/config.h"
#include "maxl/hal/hal.h"
#include "maxl/readers/step_timer.h"

// The steps of one window, as at most two runs: first a burst of steps that
// are already due at the window's start (catching up), then steps at regular
// times. Times are µs after the window's start in Q16.16, never before the
// window's linear model reaches the step's threshold.
struct MAXL_StepWindow {
  struct Run {
    uint32_t first;     // µs·2^16 after the window's start
    uint32_t interval;  // µs·2^16 between steps (0: as fast as the timer goes)
    uint8_t count;
    bool backward;
  };
  Run run[2];
  uint8_t runs;
};

class MAXL_StepGenerator;
#if defined(__AVR__) && !defined(MAXL_NO_ASM)
// MAXL_StepGenerator::stepToward on the AVR (step_generator.cpp): assembly
// that asks whether a step is due, then the count in C once one is
// (maxl_stepTowardDue, entered from the assembly: a fixed name, the same
// registers as the member).
extern "C" uint8_t maxl_stepToward(MAXL_StepGenerator* generator, int32_t units, uint8_t max, int8_t direction);
extern "C" uint8_t maxl_stepTowardDue(MAXL_StepGenerator* generator, int32_t units, uint8_t max, int8_t direction);
#endif

class MAXL_StepGenerator {
 public:
  MAXL_StepGenerator(uint8_t stepPin, uint8_t dirPin, float stepsPerUnit, bool invertDirection = false);

  // Makes the pins outputs. MAXL_Stepper calls it from MAXL_Device::begin().
  void begin();

  // Declares that the motor is at `units` without moving it (a session's
  // reference position): step count = round(units / s).
  void reference(int32_t units);
#if MAXL_STEPPER_POLLING
  // Emits every step between the motor's step and the one `units` rounds to,
  // up to MAXL_MAX_STEPS_PER_EVALUATION per call (the rest on the next calls).
  // Returns true when the motor has reached that step.
  bool moveTo(int32_t units);
#endif

  // The step count: emitted (polled), or planned (timed: MAXL_Stepper
  // subtracts what its timer has still to send).
  int32_t steps() const { return steps_; }
  // As given to the constructor (from the Q16 step size: 2^32 / (s·2^16)).
  float stepsPerUnit() const { return 4294967296.0f / ((float)sWhole_ * 65536.0f + (float)sFrac_); }
  // Units per step, rounded down (at least 1).
  int32_t unitsPerStep() const { return sWhole_ > 0 ? sWhole_ : 1; }

  // Sets the step count to n (its thresholds with it), without stepping.
  void setSteps(int32_t n);

#if MAXL_STEP_TIMER
  // ---- timed stepping
  // Plans the steps of a window of `w` µs in which the position goes from p0
  // to p1 (linearly, as far as the steps are concerned), each step held back
  // by `lag` units (>= 0) in the direction of motion, at most
  // StepChannel::MAX_RUN per run; moves the step count on by what it planned.
  // Where p0 == p1 (at rest), only the catch-up burst.
  __attribute__((noinline)) void planWindow(uint16_t w, int32_t p0, int32_t p1, int32_t lag, MAXL_StepWindow& out);
  maxl_fw::StepChannel& channel() { return channel_; }
  const maxl_fw::StepChannel& channel() const { return channel_; }
  bool pinsValid() const { return channel_.stepPin.valid && channel_.dirPin.valid; }
#endif

 private:
#if MAXL_STEPPER_POLLING
  void pulses(uint8_t count, int8_t direction);
#endif
  // Next thresholds' ceilings (see the top of this file).
  int32_t upCeil() const { return (int32_t)((uint32_t)upWhole_ + (upFrac_ != 0)); }
  int32_t downCeil() const { return (int32_t)((uint32_t)upWhole_ - (uint32_t)sWhole_ + (upFrac_ > sFrac_)); }
#if defined(__AVR__) && !defined(MAXL_NO_ASM)
  uint8_t stepToward(int32_t units, uint8_t max, int8_t direction) { return maxl_stepToward(this, units, max, direction); }
  friend uint8_t maxl_stepToward(MAXL_StepGenerator* generator, int32_t units, uint8_t max, int8_t direction);
  friend uint8_t maxl_stepTowardDue(MAXL_StepGenerator* generator, int32_t units, uint8_t max, int8_t direction);
#else
  uint8_t stepToward(int32_t units, uint8_t max, int8_t direction);
#endif
  uint8_t countToward(int32_t units, uint8_t max, int8_t direction);
  uint32_t walkToward(int32_t units, uint32_t max, int8_t direction);
  uint8_t stepsUpTo(int32_t units, uint8_t max) { return stepToward(units, max, 1); }
  uint8_t stepsDownTo(int32_t units, uint8_t max) { return stepToward(units, max, -1); }
#if MAXL_STEP_TIMER
  int32_t keptLag(bool forward, int32_t p0, int32_t lag);
#endif

#if MAXL_STEP_TIMER
  // the pins live in the channel (the interrupt's), once
  maxl_fw::hal::OutputPin& stepPin() { return channel_.stepPin; }
  maxl_fw::hal::OutputPin& dirPin() { return channel_.dirPin; }
  bool inverted() const { return channel_.invert; }
#else
  maxl_fw::hal::OutputPin& stepPin() { return stepPin_; }
  maxl_fw::hal::OutputPin& dirPin() { return dirPin_; }
  bool inverted() const { return invert_; }
  maxl_fw::hal::OutputPin stepPin_;
  maxl_fw::hal::OutputPin dirPin_;
  bool invert_;
#endif
  bool begun_;
  int8_t direction_;  // last direction written by step(): +1, -1, or 0 before the first step
  int32_t sWhole_;    // s = sWhole_ + sFrac_ / 2^16 units per step
  uint16_t sFrac_;
  int32_t upWhole_;   // (n + 1/2)·s = upWhole_ + upFrac_ / 2^16
  uint16_t upFrac_;
  int32_t steps_;
#if MAXL_STEP_TIMER
  int32_t lastLag_;  // the lag planWindow() last used (0 at rest)
  maxl_fw::StepChannel channel_;
#endif
};

#endif
