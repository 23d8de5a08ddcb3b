#include "maxl/readers/stepper.h"

#include "maxl/device/device.h"
#include "maxl/readers/step_planner.h"
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

#if MAXL_STEP_TIMER && !defined(__AVR__)
MAXL_Stepper::~MAXL_Stepper() {
  MAXL_StepPlanner::leave(this);
  StepTimer::detach(&generator_.channel());
}
#endif

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
    if (timed_) MAXL_StepPlanner::join(this);
    synced_ = false;
  } else if (!on && timed_) {
    stopTimed();
    MAXL_StepPlanner::leave(this);
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
    if (known()) MAXL_StepPlanner::plan(device, this);
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
  tookBack(dropped);
  synced_ = false;
  MAXL_StepPlanner::changed();
}

void MAXL_Stepper::dropFrom(uint32_t from) {
  uint8_t sreg = hal::lockInterrupts();
  int16_t dropped = generator_.channel().dropFrom(StepTimer::ticksAt(from));
  hal::unlockInterrupts(sreg);
  tookBack(dropped);
}

// Steps taken back from the ring were counted when planned: the count goes back.
__attribute__((noinline)) void MAXL_Stepper::tookBack(int16_t dropped) {
  generator_.setSteps((int32_t)((uint32_t)generator_.steps() - (uint32_t)(int32_t)dropped));
}

// ---- this stepper's part of the planner's grid

__attribute__((noinline)) void MAXL_Stepper::gridRestart(const Motion& motion, uint32_t from, bool drop) {
  if (drop) dropFrom(from);
  motion.lookFrom(look_, slot());
}

__attribute__((noinline)) void MAXL_Stepper::gridJoin(const Motion& motion, uint32_t t) {
  uint32_t until;
  motion.lookSpan(look_, slot(), t, until);  // crosses what lies before t
  plannedUnits_ = motion.lookAt(look_, slot(), t);
  synced_ = true;
}

__attribute__((noinline)) uint16_t MAXL_Stepper::gridWindow(const Motion& motion) const {
  return windowFor(motion.lookCurvature(look_));
}

// Where the slot would be at t (RUN or BRAKE), without moving the walk: the
// track's quadratic on a copy, chunk by chunk (fixed_point.h). Only to size a
// window, so a segment's end is not snapped to its p1 here.
__attribute__((noinline)) bool MAXL_Stepper::gridTooMany(uint32_t t, int32_t& p) const {
  FixedTrack k = look_.track;
  uint32_t x = t - look_.chunkStart;
  for (; x >= 65536ul; x -= 65536ul) k.nextChunk();
  int32_t w = (int32_t)((uint32_t)k.B + (uint32_t)mulhi16Cold(k.C, (uint16_t)x));
  p = (int32_t)((uint32_t)k.P + (uint32_t)mulhi16Cold(w, (uint16_t)x));
  return tooManySteps((int32_t)((uint32_t)p - (uint32_t)plannedUnits_));
}

__attribute__((noinline)) int32_t MAXL_Stepper::gridEnd(const Motion& motion, uint32_t t1) {
  return motion.lookAt(look_, slot(), t1);
}

__attribute__((noinline)) void MAXL_Stepper::gridPlan(const Motion& motion, uint32_t t0, uint32_t t1, int32_t p1, uint32_t now) {
  schedule(t0, t1, plannedUnits_, p1, motion.lookCurvature(look_), now);
  plannedUnits_ = p1;
}

namespace {
// c·W²/4 in units for a half acceleration C (Q0.32 units/µs²): |C|·W²/2^34,
// as two 32×16 multiplies, rounded up.
int32_t bendUnits(int32_t c, uint16_t w) {
  if (!c) return 0;
  uint32_t a = c < 0 ? (uint32_t)0 - (uint32_t)c : (uint32_t)c;  // |c|, 2^31 for INT32_MIN
  if (a > 0x7FFFFFFFul) a = 0x7FFFFFFFul;
  int32_t cw = mulhi16Cold((int32_t)a, w);           // |C|·W/2^16 (floor), < 2^31
  return (mulhi16Cold(cw, w) >> 2) + 1;              // |C|·W²/2^34, + 1 for the floors
}
}  // namespace

// More than MAXL_STEP_WINDOW_STEPS steps in a move of `delta` units. (The
// product wraps only for steps over 680 mm: windows are then shorter than
// they need be, which costs planning time, not steps.)
bool MAXL_Stepper::tooManySteps(int32_t delta) const {
  uint32_t d = delta < 0 ? (uint32_t)0 - (uint32_t)delta : (uint32_t)delta;
  return d > (uint32_t)generator_.unitsPerStep() * MAXL_STEP_WINDOW_STEPS;
}

// The longest window (a power of two) whose bend c·W²/4 = |C|·W²/2^34 is at
// most s/2^b (b = MAXL_STEP_BEND_SHIFT): with W = 2^k that is
// |C| <= s·2^(34 − b − 2k). From the longest
// window down, each halving multiplies the bound by 4 (saturating: a bound
// past 2^32 holds for every C), so there is no variable shift.
namespace {
constexpr uint8_t log2u(uint32_t x) { return x <= 1 ? 0 : (uint8_t)(1 + log2u(x >> 1)); }
const uint8_t WINDOW_MAX_SHIFT = (uint8_t)(34 - MAXL_STEP_BEND_SHIFT - 2 * log2u(MAXL_STEP_WINDOW_MAX_US));  // 11 for s/2 and 2048 µs
}  // namespace

__attribute__((noinline)) uint16_t MAXL_Stepper::windowFor(int32_t c) const {
  uint32_t a = c < 0 ? (uint32_t)0 - (uint32_t)c : (uint32_t)c;
  uint32_t s = (uint32_t)generator_.unitsPerStep();
  uint32_t bound = s >= (0x80000000ul >> WINDOW_MAX_SHIFT) ? 0xFFFFFFFFul : s << WINDOW_MAX_SHIFT;
  uint16_t w = MAXL_STEP_WINDOW_MAX_US;
  while (w > MAXL_STEP_WINDOW_MIN_US && a > bound) {
    w >>= 1;
    bound = bound >= 0x40000000ul ? 0xFFFFFFFFul : bound << 2;
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
