#include "maxl/readers/step_planner.h"

#if MAXL_STEP_TIMER

#include "maxl/device/device.h"
#include "maxl/readers/stepper.h"
#include "maxl/time/wrap.h"

using namespace maxl_fw;

MAXL_Stepper* MAXL_StepPlanner::members_[MAXL_STEP_CHANNELS];
uint8_t MAXL_StepPlanner::count_ = 0;
uint32_t MAXL_StepPlanner::planned_ = 0;
MAXL_Stepper* MAXL_StepPlanner::leader_ = 0;
uint8_t MAXL_StepPlanner::epoch_ = 0;
bool MAXL_StepPlanner::dirty_ = true;

void MAXL_StepPlanner::join(MAXL_Stepper* stepper) {
  for (uint8_t i = 0; i < count_; i++)
    if (members_[i] == stepper) return;
  if (count_ < MAXL_STEP_CHANNELS) members_[count_++] = stepper;
  dirty_ = true;
}

void MAXL_StepPlanner::leave(MAXL_Stepper* stepper) {
  for (uint8_t i = 0; i < count_; i++) {
    if (members_[i] != stepper) continue;
    for (uint8_t j = i; j + 1 < count_; j++) members_[j] = members_[j + 1];
    count_--;
    dirty_ = true;
    return;
  }
}

uint8_t MAXL_StepPlanner::active(MAXL_Stepper** out) {
  uint8_t n = 0;
  for (uint8_t i = 0; i < count_; i++)
    if (members_[i]->subscribed() && members_[i]->known()) out[n++] = members_[i];
  return n;
}

// The grid starts again for all of `steppers` (one of them is new, Motion's
// path changed other than by new timing, or the plan fell far behind). The
// lookahead never plans past what is certain, so only a HALT can have made
// planned steps wrong: HALT mode 0 from the device clock on, mode 1 from its
// time. Those steps are taken back (if still in the rings), then the plan goes
// on from Motion's new state. A plan far behind the clock (`stale`: loop()
// stalled for more than 8 ms) starts again at the clock; what the rings still
// hold goes out at once, and the windows catch the motors up.
__attribute__((noinline)) void MAXL_StepPlanner::restart(MAXL_Device& device, MAXL_Stepper* const* steppers, uint8_t n,
                                                         bool stale) {
  const Motion& motion = device.motion();
  uint32_t now = device.now();
  bool planning = false;  // some stepper follows the grid: planned_ holds
  for (uint8_t i = 0; i < n; i++) planning |= steppers[i]->synced_;
  uint32_t from = motion.haltPending() && timeBefore(now, motion.haltAt()) ? motion.haltAt() : now;
  bool drop = planning && !stale && timeBefore(from, planned_);
  if (drop || !planning || stale) planned_ = drop ? from : now;
  for (uint8_t i = 0; i < n; i++) steppers[i]->gridRestart(motion, from, drop);
  const Lookahead& first = steppers[0]->look_;  // every slot's walk has the same times
  if (first.state != Lookahead::REST && timeBefore(planned_, first.chunkStart)) planned_ = first.chunkStart;
  for (uint8_t i = 0; i < n; i++) steppers[i]->gridJoin(motion, planned_);
}

// The end of the next window from planned_ (the piece ends at `until`) and
// every stepper's position there (p1). The window is the shortest any
// stepper needs for its bend (gridWindow), halved while any stepper would get
// more than MAXL_STEP_WINDOW_STEPS steps in it (a run's count is 7 bits, and
// a burst may need the rest).
uint32_t MAXL_StepPlanner::windowEnd(const Motion& motion, MAXL_Stepper* const* steppers, uint8_t n, uint32_t until,
                                     int32_t* p1) {
  uint32_t t1 = until;
  bool sized = steppers[0]->look_.state != Lookahead::REST;  // p1[] then holds gridTooMany(t1)'s positions
  if (sized) {
    uint16_t w = MAXL_STEP_WINDOW_MAX_US;
    for (uint8_t i = 0; i < n; i++) {
      uint16_t wi = steppers[i]->gridWindow(motion);
      if (wi < w) w = wi;
    }
    for (;;) {
      t1 = (planned_ & ~(uint32_t)(w - 1)) + w;  // the next multiple of w
      if (timeBefore(until, t1)) t1 = until;
      bool tooMany = false;
      for (uint8_t i = 0; i < n; i++) tooMany |= steppers[i]->gridTooMany(t1, p1[i]);
      if (!tooMany || w <= MAXL_STEP_WINDOW_MIN_US) break;
      w >>= 1;
    }
  }
  for (uint8_t i = 0; i < n; i++)
    if (!sized || !steppers[i]->gridSized(t1)) p1[i] = steppers[i]->gridEnd(motion, t1);
  return t1;
}

// Most loops: nothing changed, and the plan is far enough ahead or the
// leader's ring is full (every stepper gets a run per window, so the rings
// fill together; planMore() checks them all). Kept small, so that such a
// loop does not pay planMore()'s register saves.
void MAXL_StepPlanner::plan(MAXL_Device& device, MAXL_Stepper* caller) {
  if (!dirty_) {
    if (caller != leader_) return;
    if (device.motion().epoch() == epoch_ &&
        (!timeBefore(planned_, device.now() + MAXL_STEP_LEAD_US) || caller->generator_.channel().free() < 2))
      return;
  }
  planMore(device, caller);
}

__attribute__((noinline)) void MAXL_StepPlanner::planMore(MAXL_Device& device, MAXL_Stepper* caller) {
  const Motion& motion = device.motion();
  uint32_t now = device.now();
  MAXL_Stepper* steppers[MAXL_STEP_CHANNELS];
  uint8_t n = active(steppers);
  if (!n || steppers[0] != caller) return;
  dirty_ = false;
  leader_ = caller;
  epoch_ = motion.epoch();
  bool fresh = true;
  for (uint8_t i = 0; i < n; i++) fresh &= steppers[i]->synced_ && steppers[i]->look_.epoch == motion.epoch();
  bool stale = fresh && timeBefore(planned_ + 8000u, now);
  if (!fresh || stale) restart(device, steppers, n, stale);
  const uint32_t horizon = now + MAXL_STEP_LEAD_US;
  int32_t p1[MAXL_STEP_CHANNELS];
  while (timeBefore(planned_, horizon)) {
    for (uint8_t i = 0; i < n; i++)
      if (steppers[i]->generator_.channel().free() < 2) return;  // a window takes up to two runs
    // Every walk goes up to planned_ (the same boundaries for every slot).
    uint32_t until = 0;
    bool certain = true;
    for (uint8_t i = 0; i < n; i++) {
      uint32_t u;
      if (!motion.lookSpan(steppers[i]->look_, steppers[i]->slot(), planned_, u))
        certain = false;
      else if (i == 0 || timeBefore(u, until))
        until = u;
    }
    uint32_t t1;
    if (certain) {
      t1 = windowEnd(motion, steppers, n, until, p1);
    } else {
      // Not certain past planned_. At rest (no timing ahead) the position
      // holds at least until the device clock: catch up to it if needed.
      if (steppers[0]->look_.state != Lookahead::REST || !timeBefore(planned_, now)) return;
      t1 = now;
      for (uint8_t i = 0; i < n; i++) p1[i] = steppers[i]->gridEnd(motion, now);
    }
    for (uint8_t i = 0; i < n; i++) steppers[i]->gridPlan(motion, planned_, t1, p1[i], now);
    planned_ = t1;
    if (!certain) return;
  }
}

#endif  // MAXL_STEP_TIMER
