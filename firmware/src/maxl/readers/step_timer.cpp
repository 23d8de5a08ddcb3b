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
  bool wasIdle = count_ == 0;
  run(count_) = r;
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
    uint8_t c = run(i).count;
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
    StepRun& r = run(i);
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
  current_.count = 0;  // the AVR fast path looks only at current_
  return dropped;
}

MAXL_STEP_ISR_INLINE void StepChannel::promote() {
  uint8_t c = (uint8_t)(count_ - 1);
  count_ = c;
  if (!c) return;
  uint8_t h = head_;
  current_ = queued_[h];
  h = (uint8_t)(h + 1);
  head_ = h >= QUEUED ? 0 : h;
}

// The interrupt's work for one channel (interrupts are off): raises the STEP
// pin if a step is due at `now` and moves the run on; the caller lowers the
// pin after the pulse (finish()).
MAXL_STEP_ISR_INLINE void StepChannel::service(uint16_t now) {
  if (!count_) return;
  StepRun& r = current_;
  if ((int16_t)(r.tick() - now) > 0) return;
  hal::writePinFromIsr(stepPin, true);
  advance(&r);
  r.count--;  // bits 0..6 are at least 1 here, so BACKWARD stays
  if (!(r.count & MAX_RUN)) promote();
}

// After the pulse: STEP low (whether or not it rose), then DIR for the next
// run (the driver latched DIR at the rising edge).
MAXL_STEP_ISR_INLINE void StepChannel::finish() {
  hal::writePinFromIsr(stepPin, false);
  if (!count_) return;
  uint8_t backward = current_.count & BACKWARD;
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
#include <avr/io.h>

// The vector, in two parts.
//
// The fast path (assembly, 7 registers saved) is the common case at high
// step rates: one channel on the timer, its step due, and not the last of
// its run. It is exactly serviceAll() for that case: STEP high, the run moved
// on (count − 1, next += interval), the compare set to the new step (or
// MAXL_STEP_MIN_TICKS from now if that is later: arm()), STEP low. The
// pulse is high for the ~60 cycles between the two stores (3.8 µs at 16 MHz,
// over the 2 µs that common drivers need), so it needs no wait; DIR cannot
// change inside a run. ~150 cycles in all, where the C handler takes ~280.
//
// Everything else (several channels, a run's last step, nothing due, the
// direction) restores every register as the interrupt found them and jumps
// to the C handler, which saves what it uses and returns with reti.
//
// The fast path reads the channel at fixed offsets: current_ (next 0..3,
// interval 4..7, count 8), then stepPin (port 9..10, mask 11). An idle
// channel's current_.count is 0 (dropAll, promote), so the count test also
// covers "no run".
namespace maxl_fw {
namespace {
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Winvalid-offsetof"
static_assert(offsetof(StepChannel, current_) == 0 && sizeof(StepRun) == 9 && offsetof(StepRun, count) == 8 &&
                  offsetof(StepChannel, stepPin) == 9 && offsetof(hal::OutputPin, port) == 0 &&
                  offsetof(hal::OutputPin, mask) == 2,
              "the step vector's fast path reads these offsets");
#pragma GCC diagnostic pop
static_assert(MAXL_STEP_MIN_TICKS <= 63, "adiw");
}  // namespace
}  // namespace maxl_fw

// The registers the fast path uses, and SREG (through r24), saved and restored.
#define MAXL_STEP_ISR_SAVE \
  "push r24\n\tin   r24, __SREG__\n\tpush r24\n\tpush r25\n\tpush r26\n\tpush r27\n\tpush r30\n\tpush r31\n\t"
#define MAXL_STEP_ISR_RESTORE \
  "pop  r31\n\tpop  r30\n\tpop  r27\n\tpop  r26\n\tpop  r25\n\tpop  r24\n\tout  __SREG__, r24\n\tpop  r24\n\t"

extern "C" void __vector_maxl_step_slow(void) __attribute__((signal, used, externally_visible));
void __vector_maxl_step_slow(void) { maxl_fw::serviceAll(); }

ISR(TIMER1_COMPB_vect, ISR_NAKED) {
  __asm__ __volatile__(
      MAXL_STEP_ISR_SAVE
      // one channel, Z = it
      "lds  r24, %[channels]\n\t"
      "cpi  r24, 1\n\t"
      "brne 9f\n\t"
      "lds  r30, %[channel0]\n\t"
      "lds  r31, %[channel0]+1\n\t"
      // at least 2 steps left in the run going out
      "ldd  r24, Z+8\n\t"
      "andi r24, 0x7F\n\t"
      "cpi  r24, 2\n\t"
      "brlo 9f\n\t"
      // due: the 16-bit difference count − tick is not negative
      "lds  r26, %[tcntl]\n\t"
      "lds  r27, %[tcnth]\n\t"
      "ldd  r24, Z+2\n\t"
      "ldd  r25, Z+3\n\t"
      "cp   r26, r24\n\t"
      "cpc  r27, r25\n\t"
      "brpl 2f\n\t"
      // everything else (here, within reach of the branches above)
      "9:\n\t"
      MAXL_STEP_ISR_RESTORE
      "jmp  __vector_maxl_step_slow\n\t"
      "2:\n\t"
      // STEP high
      "ldd  r26, Z+9\n\t"
      "ldd  r27, Z+10\n\t"
      "ldd  r25, Z+11\n\t"
      "ld   r24, X\n\t"
      "or   r24, r25\n\t"
      "st   X, r24\n\t"
      // count − 1 (BACKWARD, bit 7, stays)
      "ldd  r24, Z+8\n\t"
      "dec  r24\n\t"
      "std  Z+8, r24\n\t"
      // next += interval, byte by byte
      "ldd  r24, Z+0\n\t"
      "ldd  r25, Z+4\n\t"
      "add  r24, r25\n\t"
      "std  Z+0, r24\n\t"
      "ldd  r24, Z+1\n\t"
      "ldd  r25, Z+5\n\t"
      "adc  r24, r25\n\t"
      "std  Z+1, r24\n\t"
      "ldd  r24, Z+2\n\t"
      "ldd  r25, Z+6\n\t"
      "adc  r24, r25\n\t"
      "std  Z+2, r24\n\t"
      "ldd  r24, Z+3\n\t"
      "ldd  r25, Z+7\n\t"
      "adc  r24, r25\n\t"
      "std  Z+3, r24\n\t"
      // compare = the new tick, or count + MAXL_STEP_MIN_TICKS if that is later
      "lds  r26, %[tcntl]\n\t"
      "lds  r27, %[tcnth]\n\t"
      "adiw r26, %[minTicks]\n\t"
      "ldd  r24, Z+2\n\t"
      "ldd  r25, Z+3\n\t"
      "cp   r24, r26\n\t"
      "cpc  r25, r27\n\t"
      "brpl 1f\n\t"
      "movw r24, r26\n\t"
      "1:\n\t"
      "sts  %[ocrh], r25\n\t"
      "sts  %[ocrl], r24\n\t"
      // STEP low
      "ldd  r26, Z+9\n\t"
      "ldd  r27, Z+10\n\t"
      "ldd  r25, Z+11\n\t"
      "ld   r24, X\n\t"
      "com  r25\n\t"
      "and  r24, r25\n\t"
      "st   X, r24\n\t"
      MAXL_STEP_ISR_RESTORE
      "reti\n\t"
      :
      : [channels] "i"(&maxl_fw::StepTimer::count_), [channel0] "i"(&maxl_fw::StepTimer::channels_[0]),
        [tcntl] "n"(_SFR_MEM_ADDR(TCNT1L)), [tcnth] "n"(_SFR_MEM_ADDR(TCNT1H)), [ocrl] "n"(_SFR_MEM_ADDR(OCR1BL)),
        [ocrh] "n"(_SFR_MEM_ADDR(OCR1BH)), [minTicks] "I"(MAXL_STEP_MIN_TICKS));
}
#endif

#endif  // MAXL_STEP_TIMER
