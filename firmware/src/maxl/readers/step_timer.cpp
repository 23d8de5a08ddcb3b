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
  current_.count = 0;  // the AVR vector tests only current_ for "no run"
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
// (HOLD false: no pulse hold, for StepVectorCheck's stopped timer.)
template <bool HOLD>
MAXL_STEP_ISR_INLINE void serviceAll() {
  uint16_t now = hal::stepTimerNow();
  StepChannel* const* end = StepTimer::channels_ + StepTimer::count_;
  for (StepChannel* const* c = StepTimer::channels_; c != end; c++) (*c)->service(now);
  uint16_t rose = hal::stepTimerNow();
  StepTimer::arm();
  if (HOLD) hal::stepPulseHold(rose);
  for (StepChannel* const* c = StepTimer::channels_; c != end; c++) (*c)->finish();
}
}  // namespace

// On AVR nothing calls it (the vector below is assembly, and the linker drops
// it): it is the reference the vector is checked against in simavr
// (firmware/bench/StepVectorCheck).
void StepTimer::interrupt() { serviceAll<true>(); }
void StepTimer::interruptWithoutHold() { serviceAll<false>(); }

}  // namespace maxl_fw

#if MAXL_HAL_ARDUINO && defined(__AVR__)
#include <avr/interrupt.h>
#include <avr/io.h>

// The vector: serviceAll() in one pass of assembly over the registered
// channels (GRBL's one interrupt for all axes), for every case: a step inside
// a run, a run's last step (the next queued run copied into current_), a
// direction change, nothing due.
//
//   1. each channel, from the first: a channel with no run is skipped. If
//      its next tick is due (the 16-bit difference tick − count at entry is
//      not positive): STEP high, count − 1, next += interval, and if that was
//      the run's last step, promote() (out of line: copy the next queued run
//      in, noting a direction change); the channel's next tick then joins the
//      earliest difference. A channel not due joins it as it is;
//   2. the compare goes to the earliest next step (or MAXL_STEP_MIN_TICKS
//      from the count, if that is later: arm()); no run left anywhere:
//      the compare interrupt is turned off (stepTimerDisarm());
//   3. STEP low: where every pin that rose is on one port (the common case:
//      an Uno's STEP pins D2–D4 are all PORTD), one write with the masks
//      gathered in step 1; else every channel's STEP pin, one by one (a low
//      pin stays low, as in finish());
//   4. only if a promoted run changed direction: finish()'s DIR update for
//      every channel (the driver latched DIR at the rising edge).
//
// A pulse is high from its channel's step 1 to step 3: at least its own
// count and advance (~40 cycles), the compare (~20) and the fall (~8), ~70
// cycles, 4.4 µs at 16 MHz, over the 2 µs that common drivers need and
// MAXL_STEP_PULSE_TICKS' 2.5 µs, so it needs no wait.
//
// Each channel is read at fixed offsets (the static_asserts below): current_
// (next 0..3, interval 4..7, count 8), stepPin and dirPin (port, mask), then
// invert, head_, count_, backward_ and queued_. An idle channel's
// current_.count has no steps (dropAll, promote, dropFrom), so that one test
// covers "no run". Registers: r16 the STEP masks that rose, r17 flags (bit 0
// a run left somewhere, bit 1 STEP pins on more than one port), T a
// direction to update, r18:r19 the count at entry, r20:r21 the earliest
// difference, r25:r22 a tick or a difference, r23 a loop count, Y the channel
// list, Z a channel, X the port of the last STEP pin raised, r24 and r25
// scratch. 16 registers saved (~70 cycles of the ~270 for two due channels).
namespace maxl_fw {
namespace {
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Winvalid-offsetof"
static_assert(offsetof(StepChannel, current_) == 0 && sizeof(StepRun) == 9 && offsetof(StepRun, count) == 8 &&
                  offsetof(hal::OutputPin, port) == 0 && offsetof(hal::OutputPin, mask) == 2,
              "the step vector reads these offsets");
static_assert(offsetof(StepChannel, head_) < offsetof(StepChannel, backward_) &&
                  offsetof(StepChannel, count_) < offsetof(StepChannel, backward_) &&
                  offsetof(StepChannel, backward_) <= 63 && offsetof(StepChannel, dirPin) + 2 <= 63 &&
                  offsetof(StepChannel, queued_) <= 63,
              "the step vector reaches these members with ldd and queued_ with adiw (up to 63)");
static_assert(StepChannel::QUEUED * 9 <= 255, "head · 9 fits a byte");
#pragma GCC diagnostic pop
static_assert(MAXL_STEP_MIN_TICKS <= 63, "adiw");
static_assert(MAXL_STEP_CHANNELS >= 1 && MAXL_STEP_CHANNELS <= 255, "the step vector counts the channels in one byte");
static_assert(StepChannel::BACKWARD == 0x80 && StepChannel::MAX_RUN == 0x7F, "andi 0x7F, andi 0x80");
}  // namespace
}  // namespace maxl_fw

#define MAXL_STEP_ISR_SAVE                                                                                      \
  "push r24\n\tin   r24, __SREG__\n\tpush r24\n\tpush r25\n\tpush r26\n\tpush r27\n\tpush r30\n\tpush r31\n\t" \
  "push r16\n\tpush r17\n\tpush r18\n\tpush r19\n\tpush r20\n\tpush r21\n\tpush r22\n\tpush r23\n\tpush r28\n\t"   \
  "push r29\n\t"
#define MAXL_STEP_ISR_RESTORE                                                                                  \
  "pop  r29\n\tpop  r28\n\tpop  r23\n\tpop  r22\n\tpop  r21\n\tpop  r20\n\tpop  r19\n\tpop  r18\n\tpop  r17\n\t" \
  "pop  r16\n\tpop  r31\n\tpop  r30\n\tpop  r27\n\tpop  r26\n\tpop  r25\n\tpop  r24\n\tout  __SREG__, r24\n\t"    \
  "pop  r24\n\t"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Winvalid-offsetof"
ISR(TIMER1_COMPB_vect, ISR_NAKED) {
  __asm__ __volatile__(
      MAXL_STEP_ISR_SAVE
      "lds  r18, %[tcntl]\n\t"
      "lds  r19, %[tcnth]\n\t"
      "ldi  r20, 0xFF\n\t"  // the earliest difference so far: none
      "ldi  r21, 0x7F\n\t"
      "clr  r16\n\t"
      "clr  r17\n\t"
      "clt\n\t"
      "ldi  r28, lo8(%[ch])\n\t"
      "ldi  r29, hi8(%[ch])\n\t"
      "lds  r23, %[channels]\n\t"
      "tst  r23\n\t"
      "breq 20f\n\t"
      // 1. every channel, from the first
      "1:\n\t"
      "ld   r30, Y+\n\t"
      "ld   r31, Y+\n\t"
      "ldd  r24, Z+8\n\t"  // steps left in the run going out (0: no run)
      "andi r24, 0x7F\n\t"
      "breq 19f\n\t"
      "ldd  r22, Z+2\n\t"  // tick − count
      "ldd  r25, Z+3\n\t"
      "sub  r22, r18\n\t"
      "sbc  r25, r19\n\t"
      "breq 2f\n\t"
      "brpl 17f\n\t"
      "2:\n\t"             // due: STEP high, on the port of the pins raised so far?
      "ldd  r24, Z+%[stepPort]\n\t"
      "ldd  r25, Z+%[stepPort]+1\n\t"
      "tst  r16\n\t"
      "breq 3f\n\t"
      "cp   r24, r26\n\t"
      "cpc  r25, r27\n\t"
      "breq 3f\n\t"
      "ori  r17, 2\n\t"
      "3:\n\t"
      "movw r26, r24\n\t"
      "ldd  r25, Z+%[stepMask]\n\t"
      "or   r16, r25\n\t"
      "ld   r24, X\n\t"
      "or   r24, r25\n\t"
      "st   X, r24\n\t"
      "ldd  r24, Z+8\n\t"  // count − 1 (BACKWARD, bit 7, stays)
      "dec  r24\n\t"
      "std  Z+8, r24\n\t"
      "andi r24, 0x7F\n\t"
      "brne 4f\n\t"
      "rjmp 40f\n\t"       // the run is spent: promote(), out of line
      "4:\n\t"
      "ldd  r22, Z+0\n\t"  // next += interval, byte by byte; the tick in r25:r22
      "ldd  r24, Z+4\n\t"
      "add  r22, r24\n\t"
      "std  Z+0, r22\n\t"
      "ldd  r22, Z+1\n\t"
      "ldd  r24, Z+5\n\t"
      "adc  r22, r24\n\t"
      "std  Z+1, r22\n\t"
      "ldd  r22, Z+2\n\t"
      "ldd  r24, Z+6\n\t"
      "adc  r22, r24\n\t"
      "std  Z+2, r22\n\t"
      "ldd  r25, Z+3\n\t"
      "ldd  r24, Z+7\n\t"
      "adc  r25, r24\n\t"
      "std  Z+3, r25\n\t"
      "16:\n\t"            // the next tick − count: the earliest so far?
      "sub  r22, r18\n\t"
      "sbc  r25, r19\n\t"
      "17:\n\t"
      "ori  r17, 1\n\t"    // a run left: the compare stays on
      "cp   r22, r20\n\t"
      "cpc  r25, r21\n\t"
      "brge 19f\n\t"
      "mov  r20, r22\n\t"
      "mov  r21, r25\n\t"
      "19:\n\t"
      "dec  r23\n\t"
      "brne 1b\n\t"
      // 2. compare = count at entry + the least difference, or the count now
      // + MAXL_STEP_MIN_TICKS if that is later; nothing left: disarm
      "20:\n\t"
      "sbrs r17, 0\n\t"
      "rjmp 22f\n\t"
      "add  r20, r18\n\t"
      "adc  r21, r19\n\t"
      "lds  r24, %[tcntl]\n\t"
      "lds  r25, %[tcnth]\n\t"
      "adiw r24, %[minTicks]\n\t"
      "cp   r20, r24\n\t"
      "cpc  r21, r25\n\t"
      "brpl 21f\n\t"
      "movw r20, r24\n\t"
      "21:\n\t"
      "sts  %[ocrh], r21\n\t"
      "sts  %[ocrl], r20\n\t"
      "rjmp 23f\n\t"
      "22:\n\t"
      "lds  r24, %[timsk]\n\t"
      "andi r24, %[noCompare]\n\t"
      "sts  %[timsk], r24\n\t"
      // 3. STEP low: one port (X) and the masks gathered, or every channel's
      "23:\n\t"
      "sbrc r17, 1\n\t"
      "rjmp 25f\n\t"
      "tst  r16\n\t"
      "breq 26f\n\t"
      "ld   r24, X\n\t"
      "com  r16\n\t"
      "and  r24, r16\n\t"
      "st   X, r24\n\t"
      // 4. a promoted run changed direction: DIR follows current_ on every
      // channel with a run (finish())
      "26:\n\t"
      "brts 27f\n\t"
      "29:\n\t"
      MAXL_STEP_ISR_RESTORE
      "reti\n\t"
      // 3, STEP pins on more than one port: every channel's STEP low
      "25:\n\t"
      "ldi  r28, lo8(%[ch])\n\t"
      "ldi  r29, hi8(%[ch])\n\t"
      "lds  r23, %[channels]\n\t"
      "24:\n\t"
      "ld   r30, Y+\n\t"
      "ld   r31, Y+\n\t"
      "ldd  r26, Z+%[stepPort]\n\t"
      "ldd  r27, Z+%[stepPort]+1\n\t"
      "ldd  r25, Z+%[stepMask]\n\t"
      "ld   r24, X\n\t"
      "com  r25\n\t"
      "and  r24, r25\n\t"
      "st   X, r24\n\t"
      "dec  r23\n\t"
      "brne 24b\n\t"
      "rjmp 26b\n\t"
      // 4, out of line
      "27:\n\t"
      "ldi  r28, lo8(%[ch])\n\t"
      "ldi  r29, hi8(%[ch])\n\t"
      "lds  r23, %[channels]\n\t"
      "5:\n\t"
      "ld   r30, Y+\n\t"
      "ld   r31, Y+\n\t"
      "ldd  r24, Z+%[ring]\n\t"
      "tst  r24\n\t"
      "breq 28f\n\t"
      "ldd  r24, Z+8\n\t"
      "andi r24, 0x80\n\t"
      "ldd  r25, Z+%[backward]\n\t"
      "cp   r24, r25\n\t"
      "breq 28f\n\t"
      "std  Z+%[backward], r24\n\t"
      "ldd  r25, Z+%[invert]\n\t"  // DIR high when backward (as 0 or 1) = invert
      "tst  r24\n\t"
      "breq 30f\n\t"
      "ldi  r24, 1\n\t"
      "eor  r25, r24\n\t"           // r25 = invert XOR backward: 0 means high
      "30:\n\t"
      "ldd  r26, Z+%[dirPort]\n\t"
      "ldd  r27, Z+%[dirPort]+1\n\t"
      "ldd  r20, Z+%[dirMask]\n\t"
      "ld   r24, X\n\t"
      "tst  r25\n\t"
      "brne 31f\n\t"
      "or   r24, r20\n\t"
      "rjmp 32f\n\t"
      "31:\n\t"
      "com  r20\n\t"
      "and  r24, r20\n\t"
      "32:\n\t"
      "st   X, r24\n\t"
      "28:\n\t"
      "dec  r23\n\t"
      "brne 5b\n\t"
      "rjmp 29b\n\t"
      // 1's promote(): the run is spent (X, the STEP port, kept on the stack)
      "40:\n\t"
      "ldd  r24, Z+%[ring]\n\t"
      "dec  r24\n\t"
      "std  Z+%[ring], r24\n\t"
      "brne 41f\n\t"
      "rjmp 19b\n\t"       // no run left: this channel is idle
      "41:\n\t"
      "push r26\n\t"
      "push r27\n\t"
      "ldd  r24, Z+%[head]\n\t"
      "mov  r25, r24\n\t"  // X = &queued_[head], head · 9 = head · 8 + head
      "lsl  r25\n\t"
      "lsl  r25\n\t"
      "lsl  r25\n\t"
      "add  r25, r24\n\t"
      "movw r26, r30\n\t"
      "adiw r26, %[queued]\n\t"
      "add  r26, r25\n\t"
      "brcc 42f\n\t"
      "inc  r27\n\t"
      "42:\n\t"
      "inc  r24\n\t"       // head + 1, wrapping at QUEUED
      "cpi  r24, %[nQueued]\n\t"
      "brlo 43f\n\t"
      "clr  r24\n\t"
      "43:\n\t"
      "std  Z+%[head], r24\n\t"
      "ldi  r24, 9\n\t"    // current_ = queued_[head]
      "44:\n\t"
      "ld   r25, X+\n\t"
      "st   Z+, r25\n\t"
      "dec  r24\n\t"
      "brne 44b\n\t"
      "sbiw r30, 9\n\t"
      "pop  r27\n\t"
      "pop  r26\n\t"
      "andi r25, 0x80\n\t" // its direction (r25: the count, copied last)
      "ldd  r24, Z+%[backward]\n\t"
      "cpse r24, r25\n\t"
      "set\n\t"            // DIR after the pulses
      "ldd  r22, Z+2\n\t"
      "ldd  r25, Z+3\n\t"
      "rjmp 16b\n\t"
      :
      : [channels] "i"(&maxl_fw::StepTimer::count_), [ch] "i"(&maxl_fw::StepTimer::channels_[0]),
        [tcntl] "n"(_SFR_MEM_ADDR(TCNT1L)), [tcnth] "n"(_SFR_MEM_ADDR(TCNT1H)), [ocrl] "n"(_SFR_MEM_ADDR(OCR1BL)),
        [ocrh] "n"(_SFR_MEM_ADDR(OCR1BH)), [timsk] "n"(_SFR_MEM_ADDR(TIMSK1)), [noCompare] "n"(0xFF & ~_BV(OCIE1B)),
        [minTicks] "I"(MAXL_STEP_MIN_TICKS), [stepPort] "n"(offsetof(maxl_fw::StepChannel, stepPin)),
        [stepMask] "n"(offsetof(maxl_fw::StepChannel, stepPin) + 2), [dirPort] "n"(offsetof(maxl_fw::StepChannel, dirPin)),
        [dirMask] "n"(offsetof(maxl_fw::StepChannel, dirPin) + 2), [invert] "n"(offsetof(maxl_fw::StepChannel, invert)),
        [head] "n"(offsetof(maxl_fw::StepChannel, head_)), [ring] "n"(offsetof(maxl_fw::StepChannel, count_)),
        [backward] "n"(offsetof(maxl_fw::StepChannel, backward_)), [queued] "n"(offsetof(maxl_fw::StepChannel, queued_)),
        [nQueued] "n"(maxl_fw::StepChannel::QUEUED));
}
#pragma GCC diagnostic pop
#endif

#endif  // MAXL_STEP_TIMER
