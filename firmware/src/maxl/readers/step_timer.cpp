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
__attribute__((noinline)) void StepTimer::arm() {
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
// The fast path (assembly, 15 registers saved) is the common case at high
// step rates: every channel whose step is due has more steps left in its
// run. It is exactly serviceAll() for that case, for every channel on the
// timer in one pass (GRBL's one interrupt for all axes):
//
//   1. which channels are due (the 16-bit difference tick − count is not
//      positive); a due channel at the last step of its run sends the whole
//      interrupt to the C handler, and so does nothing due. The channels not
//      due give the earliest difference so far;
//   2. each due channel: STEP high, count − 1, next += interval, and its next
//      tick joins the earliest;
//   3. the compare goes to the earliest next step (or MAXL_STEP_MIN_TICKS
//      from the count, if that is later: arm());
//   4. each due channel: STEP low.
//
// A pulse is high from its channel's step 2 to its step 4, at least the ~40
// cycles of steps 2 (the rest), 3 and 4 (2.5 µs at 16 MHz, over the 2 µs that
// common drivers need), so it needs no wait; DIR cannot change inside a run.
// ~190 cycles for one channel, ~270 for two due at once, where the C handler
// takes ~280 for one.
//
// Everything else (a run's last step, nothing due, the direction) restores
// every register as the interrupt found them and jumps to the C handler,
// which saves what it uses and returns with reti.
//
// The fast path reads each channel at fixed offsets: current_ (next 0..3,
// interval 4..7, count 8), then stepPin (port 9..10, mask 11). An idle
// channel's current_.count is 0 (dropAll, promote), so the count test also
// covers "no run". Registers: r18:r19 the count at entry, r20:r21 a
// difference or the earliest one, r22 the due channels (bit i for channel
// i), r23 a loop count or the due channels left, Y the channel list, Z a
// channel, X a port.
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
static_assert(MAXL_STEP_CHANNELS >= 1 && MAXL_STEP_CHANNELS <= 8, "the step vector's fast path keeps a bit per channel");
}  // namespace
}  // namespace maxl_fw

#define MAXL_STEP_ISR_SAVE                                                                                      \
  "push r24\n\tin   r24, __SREG__\n\tpush r24\n\tpush r25\n\tpush r26\n\tpush r27\n\tpush r30\n\tpush r31\n\t" \
  "push r18\n\tpush r19\n\tpush r20\n\tpush r21\n\tpush r22\n\tpush r23\n\tpush r28\n\tpush r29\n\t"
#define MAXL_STEP_ISR_RESTORE                                                                                  \
  "pop  r29\n\tpop  r28\n\tpop  r23\n\tpop  r22\n\tpop  r21\n\tpop  r20\n\tpop  r19\n\tpop  r18\n\t"          \
  "pop  r31\n\tpop  r30\n\tpop  r27\n\tpop  r26\n\tpop  r25\n\tpop  r24\n\tout  __SREG__, r24\n\tpop  r24\n\t"

extern "C" void __vector_maxl_step_slow(void) __attribute__((signal, used, externally_visible));
void __vector_maxl_step_slow(void) { maxl_fw::serviceAll(); }

ISR(TIMER1_COMPB_vect, ISR_NAKED) {
  __asm__ __volatile__(
      MAXL_STEP_ISR_SAVE
      "lds  r18, %[tcntl]\n\t"
      "lds  r19, %[tcnth]\n\t"
      "ldi  r20, 0xFF\n\t"
      "ldi  r21, 0x7F\n\t"
      "clr  r22\n\t"
      // 1. the channels from the last to the first (Y from the end of the list)
      "lds  r23, %[channels]\n\t"
      "tst  r23\n\t"
      "breq 9f\n\t"
      "mov  r24, r23\n\t"
      "lsl  r24\n\t"
      "ldi  r28, lo8(%[ch])\n\t"
      "ldi  r29, hi8(%[ch])\n\t"
      "add  r28, r24\n\t"
      "brcc 1f\n\t"
      "inc  r29\n\t"
      "1:\n\t"
      "ld   r31, -Y\n\t"
      "ld   r30, -Y\n\t"
      "lsl  r22\n\t"
      "ldd  r24, Z+8\n\t"  // steps left in the run going out (0: no run)
      "andi r24, 0x7F\n\t"
      "breq 2f\n\t"
      "ldd  r26, Z+2\n\t"  // tick − count
      "ldd  r27, Z+3\n\t"
      "sub  r26, r18\n\t"
      "sbc  r27, r19\n\t"
      "breq 3f\n\t"
      "brpl 4f\n\t"
      "3:\n\t"             // due: more than this step left, or the C handler
      "cpi  r24, 2\n\t"
      "brlo 9f\n\t"
      "ori  r22, 1\n\t"
      "rjmp 2f\n\t"
      "4:\n\t"             // not due: the earliest so far?
      "cp   r26, r20\n\t"
      "cpc  r27, r21\n\t"
      "brge 2f\n\t"
      "movw r20, r26\n\t"
      "2:\n\t"
      "dec  r23\n\t"
      "brne 1b\n\t"
      "tst  r22\n\t"
      "brne 8f\n\t"
      // everything else: the C handler
      "9:\n\t"
      MAXL_STEP_ISR_RESTORE
      "jmp  __vector_maxl_step_slow\n\t"
      "8:\n\t"
      // 2. the due channels, from the first
      "ldi  r28, lo8(%[ch])\n\t"
      "ldi  r29, hi8(%[ch])\n\t"
      "mov  r23, r22\n\t"
      "5:\n\t"
      "ld   r30, Y+\n\t"
      "ld   r31, Y+\n\t"
      "lsr  r23\n\t"
      "brcc 6f\n\t"
      "ldd  r26, Z+9\n\t"  // STEP high
      "ldd  r27, Z+10\n\t"
      "ldd  r25, Z+11\n\t"
      "ld   r24, X\n\t"
      "or   r24, r25\n\t"
      "st   X, r24\n\t"
      "ldd  r24, Z+8\n\t"  // count − 1 (BACKWARD, bit 7, stays)
      "dec  r24\n\t"
      "std  Z+8, r24\n\t"
      "ldd  r24, Z+0\n\t"  // next += interval, byte by byte
      "ldd  r25, Z+4\n\t"
      "add  r24, r25\n\t"
      "std  Z+0, r24\n\t"
      "ldd  r24, Z+1\n\t"
      "ldd  r25, Z+5\n\t"
      "adc  r24, r25\n\t"
      "std  Z+1, r24\n\t"
      "ldd  r26, Z+2\n\t"
      "ldd  r25, Z+6\n\t"
      "adc  r26, r25\n\t"
      "std  Z+2, r26\n\t"
      "ldd  r27, Z+3\n\t"
      "ldd  r25, Z+7\n\t"
      "adc  r27, r25\n\t"
      "std  Z+3, r27\n\t"
      "sub  r26, r18\n\t"  // the new tick − count: the earliest so far?
      "sbc  r27, r19\n\t"
      "cp   r26, r20\n\t"
      "cpc  r27, r21\n\t"
      "brge 6f\n\t"
      "movw r20, r26\n\t"
      "6:\n\t"
      "tst  r23\n\t"
      "brne 5b\n\t"
      // 3. compare = count at entry + the least difference, or the count now
      // + MAXL_STEP_MIN_TICKS if that is later
      "add  r20, r18\n\t"
      "adc  r21, r19\n\t"
      "lds  r26, %[tcntl]\n\t"
      "lds  r27, %[tcnth]\n\t"
      "adiw r26, %[minTicks]\n\t"
      "cp   r20, r26\n\t"
      "cpc  r21, r27\n\t"
      "brpl 7f\n\t"
      "movw r20, r26\n\t"
      "7:\n\t"
      "sts  %[ocrh], r21\n\t"
      "sts  %[ocrl], r20\n\t"
      // 4. STEP low on the due channels
      "ldi  r28, lo8(%[ch])\n\t"
      "ldi  r29, hi8(%[ch])\n\t"
      "5:\n\t"
      "ld   r30, Y+\n\t"
      "ld   r31, Y+\n\t"
      "lsr  r22\n\t"
      "brcc 6f\n\t"
      "ldd  r26, Z+9\n\t"
      "ldd  r27, Z+10\n\t"
      "ldd  r25, Z+11\n\t"
      "ld   r24, X\n\t"
      "com  r25\n\t"
      "and  r24, r25\n\t"
      "st   X, r24\n\t"
      "6:\n\t"
      "tst  r22\n\t"
      "brne 5b\n\t"
      MAXL_STEP_ISR_RESTORE
      "reti\n\t"
      :
      : [channels] "i"(&maxl_fw::StepTimer::count_), [ch] "i"(&maxl_fw::StepTimer::channels_[0]),
        [tcntl] "n"(_SFR_MEM_ADDR(TCNT1L)), [tcnth] "n"(_SFR_MEM_ADDR(TCNT1H)), [ocrl] "n"(_SFR_MEM_ADDR(OCR1BL)),
        [ocrh] "n"(_SFR_MEM_ADDR(OCR1BH)), [minTicks] "I"(MAXL_STEP_MIN_TICKS));
}
#endif

#endif  // MAXL_STEP_TIMER
