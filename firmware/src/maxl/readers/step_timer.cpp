#include "maxl/readers/step_timer.h"

#include <stddef.h>

#if MAXL_STEP_TIMER

// The interrupt's code is inlined into the vector, so that it saves only the
// registers it uses (a call would make it save every call-clobbered one).
#define MAXL_STEP_ISR_INLINE inline __attribute__((always_inline))

namespace maxl_fw {

StepChannel* StepTimer::channels_[MAXL_STEP_CHANNELS];
uint8_t StepTimer::count_ = 0;

namespace {
static_assert(offsetof(StepRun, next) == 0 && offsetof(StepRun, interval) == 4, "advance() adds byte 4+i to byte i");
// r->next += r->interval, byte by byte (on AVR two registers, not eight).
MAXL_STEP_ISR_INLINE void advance(StepRun* r) {
#if defined(__AVR__)
  uint8_t a, b;
  __asm__ __volatile__(
      "ldd %0, %a2+0\n\tldd %1, %a2+4\n\tadd %0, %1\n\tstd %a2+0, %0\n\t"
      "ldd %0, %a2+1\n\tldd %1, %a2+5\n\tadc %0, %1\n\tstd %a2+1, %0\n\t"
      "ldd %0, %a2+2\n\tldd %1, %a2+6\n\tadc %0, %1\n\tstd %a2+2, %0\n\t"
      "ldd %0, %a2+3\n\tldd %1, %a2+7\n\tadc %0, %1\n\tstd %a2+3, %0"
      : "=&r"(a), "=&r"(b)
      : "b"(r)
      : "memory");
#else
  r->next += r->interval;
#endif
}
}  // namespace

// ---------------------------------------------------------------- channel

void StepChannel::setDirection(uint8_t backward) {
  if (backward == backward_) return;
  backward_ = backward;
  hal::writePinFromIsr(dirPin, (backward == 0) != invert);
}

void StepChannel::push(uint32_t next, uint32_t interval, uint8_t count, bool backward) {
  StepRun r;
  r.next = next + 0xFFFFu;  // the integer part becomes the ceiling: never early
  r.interval = interval;
  r.count = (uint8_t)((count & MAX_RUN) | (backward ? BACKWARD : 0));
  uint8_t sreg = hal::lockInterrupts();
  ring_[index(count_)] = r;
  bool wasIdle = count_ == 0;
  count_ = (uint8_t)(count_ + 1);
  if (wasIdle) {
    setDirection(r.count & BACKWARD);
    StepTimer::kick();
  }
  hal::unlockInterrupts(sreg);
}

int16_t StepChannel::pending() const {
  int16_t n = 0;
  uint8_t sreg = hal::lockInterrupts();
  for (uint8_t i = 0; i < count_; i++) {
    uint8_t c = ring_[index(i)].count;
    n = (int16_t)(n + ((c & BACKWARD) ? -(int16_t)(c & MAX_RUN) : (int16_t)(c & MAX_RUN)));
  }
  hal::unlockInterrupts(sreg);
  return n;
}

// Runs are in time order, so once a run is cut short every later one goes.
__attribute__((noinline)) int16_t StepChannel::dropFrom(uint32_t tick) {
  int16_t dropped = 0;
  uint8_t keep = count_;
  for (uint8_t i = 0; i < count_; i++) {
    StepRun& r = ring_[index(i)];
    uint8_t n = r.count & MAX_RUN;
    uint8_t k = n;
    if (i >= keep) {
      k = 0;
    } else {
      // steps j = 0..n-1 at next + j·interval (unbiased); keep those before `tick`
      uint32_t t = r.next - 0xFFFFu;
      for (k = 0; k < n && (int32_t)(t - tick) < 0; k++) t += r.interval;
    }
    if (k < n) {
      int16_t gone = (int16_t)(n - k);
      dropped = (int16_t)(dropped + ((r.count & BACKWARD) ? -gone : gone));
      r.count = (uint8_t)((r.count & BACKWARD) | k);
      if (keep > i) keep = k ? (uint8_t)(i + 1) : i;
    }
  }
  count_ = keep;
  StepTimer::kick();
  return dropped;
}

int16_t StepChannel::dropAll() {
  int16_t dropped = pending();
  count_ = 0;
  return dropped;
}

// The interrupt's work for one channel (interrupts are off): raises the STEP
// pin if a step is due at `now` and moves the ring on; the caller lowers the
// pin after the pulse (finish()).
MAXL_STEP_ISR_INLINE void StepChannel::service(uint16_t now) {
  if (!count_) return;
  StepRun& r = ring_[head_];
  if ((int16_t)(r.tick() - now) > 0) return;
  hal::writePinFromIsr(stepPin, true);
  advance(&r);
  r.count--;  // bits 0..6 are at least 1 here, so BACKWARD stays
  if (!(r.count & MAX_RUN)) {
    uint8_t h = (uint8_t)(head_ + 1);
    head_ = h >= MAXL_STEP_RING ? 0 : h;
    count_ = (uint8_t)(count_ - 1);
  }
}

// After the pulse: STEP low (whether or not it rose), then DIR for the next
// run (the driver latched DIR at the rising edge).
MAXL_STEP_ISR_INLINE void StepChannel::finish() {
  hal::writePinFromIsr(stepPin, false);
  if (!count_) return;
  uint8_t backward = ring_[head_].count & BACKWARD;
  if (backward == backward_) return;
  backward_ = backward;
  hal::writePinFromIsr(dirPin, (backward == 0) != invert);
}

// ---------------------------------------------------------------- timer

bool StepTimer::attach(StepChannel* channel) {
  for (uint8_t i = 0; i < count_; i++)
    if (channels_[i] == channel) return true;
  if (count_ >= MAXL_STEP_CHANNELS) return false;
#if MAXL_HAL_ARDUINO
  hal::stepTimerBegin(0);  // the vector is below
#else
  hal::stepTimerBegin(&StepTimer::interrupt);
#endif
  uint8_t sreg = hal::lockInterrupts();
  channels_[count_] = channel;
  count_ = (uint8_t)(count_ + 1);
  hal::unlockInterrupts(sreg);
  return true;
}

void StepTimer::detach(StepChannel* channel) {
  uint8_t sreg = hal::lockInterrupts();
  for (uint8_t i = 0; i < count_; i++) {
    if (channels_[i] != channel) continue;
    for (uint8_t j = i; j + 1 < count_; j++) channels_[j] = channels_[j + 1];
    count_ = (uint8_t)(count_ - 1);
    break;
  }
  arm();
  hal::unlockInterrupts(sreg);
}

// The compare goes to the earliest next step of all channels (interrupts off).
MAXL_STEP_ISR_INLINE void StepTimer::arm() {
  uint16_t now = hal::stepTimerNow();
  bool any = false;
  uint16_t earliest = 0;
  for (uint8_t i = 0; i < count_; i++) {
    StepChannel* c = channels_[i];
    uint16_t at;
    if (!c->nextDue(at)) continue;
    if (!any || (int16_t)(at - now) < (int16_t)(earliest - now)) earliest = at;
    any = true;
  }
  if (any)
    hal::stepTimerArm(earliest);
  else
    hal::stepTimerDisarm();
}

void StepTimer::kick() {
  uint8_t sreg = hal::lockInterrupts();
  arm();
  hal::unlockInterrupts(sreg);
}

namespace {
// Every due channel's STEP pin rises and its ring moves on, the compare is
// set while the pulses are high, then every STEP pin falls (a low pin stays
// low) and DIR follows the next run.
MAXL_STEP_ISR_INLINE void serviceAll() {
  uint16_t now = hal::stepTimerNow();
  StepChannel* const* end = StepTimer::channels_ + StepTimer::count_;
  for (StepChannel* const* c = StepTimer::channels_; c != end; c++) (*c)->service(now);
  uint16_t rose = hal::stepTimerNow();
  StepTimer::arm();
  hal::stepPulseHold(rose);
  for (StepChannel* const* c = StepTimer::channels_; c != end; c++) (*c)->finish();
}
}  // namespace

#if !MAXL_HAL_ARDUINO
void StepTimer::interrupt() { serviceAll(); }
#endif

}  // namespace maxl_fw

#if MAXL_HAL_ARDUINO && defined(__AVR__)
#include <avr/interrupt.h>
ISR(TIMER1_COMPB_vect) { maxl_fw::serviceAll(); }
#endif

#endif  // MAXL_STEP_TIMER
