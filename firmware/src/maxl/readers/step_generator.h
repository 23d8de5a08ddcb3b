// Turns a position track into step and direction pulses.
//
// The motor is at step n when the position p (units of 2^-16 mm) is within
// half a step of n·s, s = 65536 / stepsPerUnit units per step:
//   n = floor(p/s + 1/2), i.e. (n − 1/2)·s <= p < (n + 1/2)·s.
// So one step up is due when p reaches (n + 1/2)·s, one down when p falls
// below (n − 1/2)·s. The upper threshold is kept exactly, as whole units plus
// a 16-bit fraction (s is too: sWhole + sFrac/2^16), and both thresholds as
// their ceilings in whole units, since p is whole: p >= x  <=>  p >= ceil(x),
// and p < x  <=>  p < ceil(x). Then "is a step due?" is two 32-bit compares,
// a step moves the thresholds with 32-bit additions, and an evaluation that
// moved p by k steps emits all k (the paper's prototype emitted at most one
// per call, capping the step rate at the loop rate).
#ifndef MAXL_READERS_STEP_GENERATOR_H
#define MAXL_READERS_STEP_GENERATOR_H

#include <stdint.h>

#include "maxl/config.h"
#include "maxl/hal/hal.h"

class MAXL_StepGenerator {
 public:
  MAXL_StepGenerator(uint8_t stepPin, uint8_t dirPin, float stepsPerUnit, bool invertDirection = false);

  // Makes the pins outputs. MAXL_Stepper calls it from MAXL_Device::begin().
  void begin();

  // Declares that the motor is at `units` without moving it (a session's
  // reference position): step count = round(units / s).
  void reference(int32_t units);
  // Emits every step between the motor's step and the one `units` rounds to,
  // up to MAXL_MAX_STEPS_PER_EVALUATION per call (the rest on the next calls).
  // Returns true when the motor has reached that step.
  bool moveTo(int32_t units);

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
  int32_t sWhole_;    // s = sWhole_ + sFrac_ / 2^16 units per step
  uint16_t sFrac_;
  int32_t upWhole_;   // (n + 1/2)·s = upWhole_ + upFrac_ / 2^16
  uint16_t upFrac_;
  int32_t upCeil_;    // ceil((n + 1/2)·s)
  int32_t downCeil_;  // ceil((n − 1/2)·s)
  int32_t steps_;
};

#endif
