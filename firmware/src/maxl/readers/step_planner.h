// One window grid per device for all its timed steppers (MAXL_STEP_TIMER).
//
// GRBL plans one block for all its axes and steps them from one interrupt;
// in MAXL's time-based form the device plans one grid of windows for all its
// steppers, once: the window boundaries, their lengths and the walk across
// phases and segments are decided once per window, and each stepper only
// evaluates its slot at the window's end and turns its window into step
// times (MAXL_StepWindow). The step timer then serves every stepper's due
// steps in one interrupt (step_timer.h).
//
// A window [t0, t1] ends at the next multiple of W after t0 (W a power of
// two), or earlier where the path's piece ends (a phase, a segment, a brake
// piece, a pending HALT: the same instants for every slot, since every slot
// follows the same σ(t)). W is the shortest window any stepper needs: the
// longest whose bend c·W²/4 stays under s/2^MAXL_STEP_BEND_SHIFT (s/2) for
// that stepper's slot
// (stepper.h), halved while any stepper would get more than
// MAXL_STEP_WINDOW_STEPS steps in it.
//
// The planner runs from the first subscribed timed stepper's onTick (once per
// loop). Steppers join the grid when they first know their position: any
// change in who takes part, a new epoch of Motion's path (a HALT, braking, a
// new session) or a plan left more than 8 ms behind the clock starts the grid
// again for all of them, each taking back the steps it planned past the new
// start.
#ifndef MAXL_READERS_STEP_PLANNER_H
#define MAXL_READERS_STEP_PLANNER_H

#include <stdint.h>

#include "maxl/config.h"

#if MAXL_STEP_TIMER

class MAXL_Device;
class MAXL_Stepper;
namespace maxl_fw {
class Motion;
}

class MAXL_StepPlanner {
 public:
  // A stepper that steps from the timer takes part (at most MAXL_STEP_CHANNELS).
  static void join(MAXL_Stepper* stepper);
  static void leave(MAXL_Stepper* stepper);
  // Called by every timed stepper's onTick; plans when `caller` is the first
  // stepper taking part.
  static void plan(MAXL_Device& device, MAXL_Stepper* caller);

 private:
  static void planMore(MAXL_Device& device, MAXL_Stepper* caller);
  // The steppers taking part now (subscribed, position known); returns how many.
  static uint8_t active(MAXL_Stepper** out);
  static void restart(MAXL_Device& device, MAXL_Stepper* const* steppers, uint8_t n, bool stale);
  static uint32_t windowEnd(const maxl_fw::Motion& motion, MAXL_Stepper* const* steppers, uint8_t n, uint32_t until,
                            int32_t* p1);

  static MAXL_Stepper* members_[MAXL_STEP_CHANNELS];
  static uint8_t count_;
  static uint32_t planned_;  // device µs the plan reaches
  static MAXL_Stepper* leader_;  // the stepper that plans (the first taking part)
  static uint8_t epoch_;     // Motion's epoch when the leader last planned
  static bool dirty_;        // who takes part may have changed: find the leader again
 public:
  // A stepper stopped or started following the grid (MAXL_Stepper::stopTimed).
  static void changed() { dirty_ = true; }
};

#endif  // MAXL_STEP_TIMER
#endif
