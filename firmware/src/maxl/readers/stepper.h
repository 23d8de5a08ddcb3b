// A position reader that drives a stepper driver directly (step/dir pins),
// from the integer position: no float work per evaluation.
//
//   MAXL_Stepper stepper("stepper", 2 /*step*/, 5 /*dir*/, 80.0f /*steps/mm*/);
//
// It is the efficient form of the paper's Listing 3 (a
// MAXL_TrackPositionLinear whose callback counts steps), with every due step
// emitted (see step_generator.h).
#ifndef MAXL_READERS_STEPPER_H
#define MAXL_READERS_STEPPER_H

#include <stdint.h>

#include "maxl/readers/step_generator.h"
#include "maxl/readers/tracks.h"

class MAXL_Stepper : public MAXL_TrackPositionLinear {
 public:
  MAXL_Stepper(const char* name, uint8_t stepPin, uint8_t dirPin, float stepsPerUnit, bool invertDirection = false)
      : MAXL_TrackPositionLinear(name), generator_(stepPin, dirPin, stepsPerUnit, invertDirection) {}

  MAXL_StepGenerator& generator() { return generator_; }
  int32_t steps() const { return generator_.steps(); }

 protected:
  void onBegin() { generator_.begin(); }
  void onPosition(int32_t units, bool first) {
    if (first)
      generator_.reference(units);
    else
      behind_ = !generator_.moveTo(units);
  }
  // A bounded catch-up (see MAXL_MAX_STEPS_PER_EVALUATION) goes on even when
  // the position does not change any more.
  void onTick(MAXL_Device& device) {
    MAXL_TrackPositionLinear::onTick(device);
    if (behind_) behind_ = !generator_.moveTo(positionUnits());
  }

 private:
  MAXL_StepGenerator generator_;
  bool behind_ = false;
};

#endif
