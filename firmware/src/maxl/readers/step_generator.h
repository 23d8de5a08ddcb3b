// Turns a position track into step and direction pulses.
//
// The motor is at step n when the position p (units of 2^-16 mm) is within
// half a step of n·s, s = 65536 / stepsPerUnit units per step:
//   n = floor(p/s + 1/2), i.e. (n − 1/2)·s <= p < (n + 1/2)·s.
// So one step up is due when p reaches (n + 1/2)·s, one down when p falls
// below (n − 1/2)·s. Both thresholds are kept in Q16 (int64) and, for the
// per-evaluation check, as their ceilings in whole units: then "is a step
// due?" is two 32-bit compares, and an evaluation that moved p by k steps
// emits all k of them (the paper's prototype emitted at most one per call,
// capping the step rate at the loop rate).
#ifndef MAXL_READERS_STEP_GENERATOR_H
#define MAXL_READERS_STEP_GENERATOR_H

#include <stdint.h>

#include "maxl/hal/hal.h"

class MAXL_StepGenerator {
 public:
  MAXL_StepGenerator(uint8_t stepPin, uint8_t dirPin, float stepsPerUnit, bool invertDirection = false);

  // Makes the pins outputs. MAXL_Stepper calls it from MAXL_Device::begin().
  void begin();

  // Declares that the motor is at `units` without moving it (a session's
  // reference position): step count = round(units / s).
  void reference(int32_t units);
  // Emits every step between the motor's step and the one `units` rounds to.
  void moveTo(int32_t units);

  int32_t steps() const { return steps_; }
  float stepsPerUnit() const { return stepsPerUnit_; }

 private:
  void refreshCeilings();
  void step(int8_t direction);

  maxl_fw::hal::OutputPin stepPin_;
  maxl_fw::hal::OutputPin dirPin_;
  uint8_t stepPinNumber_;
  uint8_t dirPinNumber_;
  bool invert_;
  bool begun_;
  int8_t direction_;  // last direction written: +1, -1, or 0 before the first step
  float stepsPerUnit_;
  int64_t stepQ_;     // s in Q16: units per step · 2^16
  int64_t upQ_;       // (n + 1/2)·s in Q16
  int32_t upCeil_;    // ceil(upQ_ / 2^16)
  int32_t downCeil_;  // ceil((upQ_ − stepQ_) / 2^16)
  int32_t steps_;
};

#endif
