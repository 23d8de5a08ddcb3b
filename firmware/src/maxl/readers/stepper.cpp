#include "maxl/readers/stepper.h"

#include "maxl/device/device.h"
#include "maxl/time/wrap.h"

using namespace maxl_fw;

MAXL_Stepper::MAXL_Stepper(const char* name, uint8_t stepPin, uint8_t dirPin, float stepsPerUnit, bool invertDirection)
    : MAXL_TrackPositionLinear(name),
      generator_(stepPin, dirPin, stepsPerUnit, invertDirection),
      behind_(false),
      timed_(false)
#if MAXL_STEP_TIMER
      ,
      wantTimer_(MAXL_STEP_TIMER_DEFAULT != 0),
      synced_(false)  // planned_, plannedUnits_ and look_ are set by resync() before use
#endif
{
}

void MAXL_Stepper::onBegin() {
  generator_.begin();
#if MAXL_STEP_TIMER
  if (wantTimer_) useStepTimer(true);
#endif
}

bool MAXL_Stepper::useStepTimer(bool on) {
#if !MAXL_STEPPER_POLLING
  on = true;  // timed stepping is all there is
#endif
#if MAXL_STEP_TIMER
  wantTimer_ = on;
  if (on && !timed_) {
    generator_.begin();
    timed_ = generator_.pinsValid() && StepTimer::attach(&generator_.channel());
    synced_ = false;
  } else if (!on && timed_) {
    stopTimed();
    StepTimer::detach(&generator_.channel());
    timed_ = false;
  }
  return timed_;
#else
  (void)on;
  return false;
#endif
}

int32_t MAXL_Stepper::steps() const {
#if MAXL_STEP_TIMER
  if (timed_) return (int32_t)((uint32_t)generator_.steps() - (uint32_t)(int32_t)generator_.channel().pending());
#endif
  return generator_.steps();
}

void MAXL_Stepper::onPosition(int32_t units, bool first) {
  if (first) {
#if MAXL_STEP_TIMER
    if (timed_) stopTimed();
#endif
    generator_.reference(units);
    return;
  }
#if MAXL_STEPPER_POLLING
  if (!timed_) behind_ = !generator_.moveTo(units);
#endif
}

// A bounded catch-up (see MAXL_MAX_STEPS_PER_EVALUATION) goes on even when
// the position does not change any more.
void MAXL_Stepper::onTick(MAXL_Device& device) {
  MAXL_TrackPositionLinear::onTick(device);
#if MAXL_STEP_TIMER
  if (timed_) {
    if (known()) plan(device);
    return;
  }
#endif
#if MAXL_STEPPER_POLLING
  if (behind_) behind_ = !generator_.moveTo(positionUnits());
#endif
}

void MAXL_Stepper::onUnsubscribe() {
  MAXL_TrackPositionLinear::onUnsubscribe();
#if MAXL_STEP_TIMER
  if (timed_) stopTimed();
#endif
  behind_ = false;
}

#if MAXL_STEP_TIMER

// Drops every step not yet out: the count is then the motor's.
void MAXL_Stepper::stopTimed() {
  uint8_t sreg = hal::lockInterrupts();
  int16_t dropped = generator_.channel().clear();
  StepTimer::kick();
  hal::unlockInterrupts(sreg);
  generator_.setSteps((int32_t)((uint32_t)generator_.steps() - (uint32_t)(int32_t)dropped));
  synced_ = false;
}

// Motion's path changed other than by new timing (its epoch moved on). The
// lookahead never plans past what is certain, so only a HALT can have made
// planned steps wrong: HALT mode 0 from the device clock on, mode 1 from its
// time. Those steps are taken back (if still in the ring), then the plan goes
// on from Motion's new state.
__attribute__((noinline)) void MAXL_Stepper::resync(const Motion& motion, uint32_t now) {
  if (synced_) {
    uint32_t from = motion.haltPending() && timeBefore(now, motion.haltAt()) ? motion.haltAt() : now;
    if (timeBefore(from, planned_)) {
      uint8_t sreg = hal::lockInterrupts();
      int16_t dropped = generator_.channel().dropFrom(StepTimer::ticksAt(from));
      hal::unlockInterrupts(sreg);
      generator_.setSteps((int32_t)((uint32_t)generator_.steps() - (uint32_t)(int32_t)dropped));
      planned_ = from;
    }
  } else {
    planned_ = now;
  }
  uint8_t slot = this->slot();
  int32_t here = motion.lookFrom(look_, slot);
  if (look_.state != Lookahead::REST && timeBefore(planned_, look_.chunkStart)) planned_ = look_.chunkStart;
  uint32_t until;
  motion.lookSpan(look_, slot, planned_, until);  // crosses what lies before planned_
  (void)here;
  plannedUnits_ = motion.lookAt(look_, slot, planned_);
  synced_ = true;
}

namespace {
// c·W²/4 in units for a half acceleration C (Q0.32 units/µs²): |C|·W²/2^34,
// as two 32×16 multiplies, rounded up.
int32_t bendUnits(int32_t c, uint16_t w) {
  if (!c) return 0;
  uint32_t a = (uint32_t)(c < 0 ? -(int64_t)c : c);
  if (a > 0x7FFFFFFFul) a = 0x7FFFFFFFul;
  int32_t cw = mulhi16Cold((int32_t)a, w);           // |C|·W/2^16 (floor), < 2^31
  return (mulhi16Cold(cw, w) >> 2) + 1;              // |C|·W²/2^34, + 1 for the floors
}
}  // namespace

__attribute__((noinline)) void MAXL_Stepper::plan(MAXL_Device& device) {
  const Motion& motion = device.motion();
  uint32_t now = device.now();
  // A plan far behind the clock (loop() stalled for more than 8 ms, far past
  // the lead): start again from Motion at the clock; what the ring still
  // holds goes out at once, and the windows catch the motor up.
  if (synced_ && timeBefore(planned_ + 8000u, now)) synced_ = false;
  if (!synced_ || look_.epoch != motion.epoch()) resync(motion, now);
  StepChannel& channel = generator_.channel();
  uint8_t slot = this->slot();
  const uint32_t horizon = now + MAXL_STEP_LEAD_US;
  while (timeBefore(planned_, horizon) && channel.free() >= 2) {
    uint32_t until;
    if (!motion.lookSpan(look_, slot, planned_, until)) {
      // Not certain past planned_. At rest (no timing ahead) the position
      // holds at least until the device clock: catch up to it if needed.
      if (look_.state == Lookahead::REST && timeBefore(planned_, now)) {
        int32_t here = motion.lookAt(look_, slot, now);
        schedule(planned_, now, here, here, 0, now);
        planned_ = now;
        plannedUnits_ = here;
      }
      break;
    }
    uint32_t t1 = until;
    int32_t c = motion.lookCurvature(look_);
    int32_t p1;
    if (look_.state != Lookahead::REST) {
      // A window holds at most MAXL_STEP_WINDOW_STEPS steps (a run's count is
      // 7 bits, and a burst may need the rest): where it would hold more, the
      // lookahead goes back (a copy) and the window is halved.
      uint16_t w = windowFor(c);
      Lookahead before = look_;
      for (;;) {
        uint32_t grid = (planned_ & ~(uint32_t)(w - 1)) + w;  // next multiple of w
        if (timeBefore(grid, t1)) t1 = grid;
        p1 = motion.lookAt(look_, slot, t1);
        if (w <= MAXL_STEP_WINDOW_MIN_US || !tooManySteps((int32_t)((uint32_t)p1 - (uint32_t)plannedUnits_))) break;
        look_ = before;
        w >>= 1;
      }
    } else {
      p1 = motion.lookAt(look_, slot, t1);
    }
    schedule(planned_, t1, plannedUnits_, p1, c, now);
    planned_ = t1;
    plannedUnits_ = p1;
  }
}

// More than MAXL_STEP_WINDOW_STEPS steps in a move of `delta` units. (The
// product wraps only for steps over 680 mm: windows are then shorter than
// they need be, which costs planning time, not steps.)
bool MAXL_Stepper::tooManySteps(int32_t delta) const {
  uint32_t d = delta < 0 ? (uint32_t)0 - (uint32_t)delta : (uint32_t)delta;
  return d > (uint32_t)generator_.unitsPerStep() * MAXL_STEP_WINDOW_STEPS;
}

// The longest window (a power of two) whose bend c·W²/4 = |C|·W²/2^34 is at
// most s/8: with W = 2^k that is |C| <= s·2^(31 − 2k), a shift per k.
uint16_t MAXL_Stepper::windowFor(int32_t c) const {
  uint32_t a = c < 0 ? (uint32_t)0 - (uint32_t)c : (uint32_t)c;
  uint32_t s = (uint32_t)generator_.unitsPerStep();
  uint16_t w = MAXL_STEP_WINDOW_MAX_US;
  uint8_t k = 0;
  while ((1u << k) < w) k++;
  for (; w > MAXL_STEP_WINDOW_MIN_US; w >>= 1, k--) {
    uint8_t shift = (uint8_t)(31 - 2 * k);  // k <= 11: shift >= 9
    if (s >= (0x80000000ul >> shift) || a <= (s << shift)) break;
  }
  return w;
}

// One window [t0, t1] from p0 to p1 on a piece of half acceleration c.
void MAXL_Stepper::schedule(uint32_t t0, uint32_t t1, int32_t p0, int32_t p1, int32_t c, uint32_t now) {
  uint32_t span = t1 - t0;
  uint16_t w = span > 0xFFFFu ? 0xFFFFu : (uint16_t)span;
  int32_t delta = (int32_t)((uint32_t)p1 - (uint32_t)p0);
  int32_t lag = MAXL_STEP_LAG_UNITS;
  if (c != 0 && delta != 0 && ((c > 0) == (delta > 0))) lag += bendUnits(c, w);  // speeding up
  MAXL_StepWindow plan;
  generator_.planWindow(w, p0, p1, lag, plan);
  if (!plan.runs) return;
  // A window far behind the clock (a very long stall): its steps go now, as
  // fast as the timer goes, so that no time in the ring is stale enough to
  // wrap the 16-bit count.
  bool stale = timeBefore(t0 + 8000u, now);
  uint32_t base = StepTimer::ticksAt(stale ? now : t0);
  StepChannel& channel = generator_.channel();
  for (uint8_t i = 0; i < plan.runs; i++) {
    const MAXL_StepWindow::Run& r = plan.run[i];
    channel.push(stale ? base : base + 2 * r.first, stale ? 0 : 2 * r.interval, r.count, r.backward);
  }
}

#endif  // MAXL_STEP_TIMER
