#include "maxl/readers/step_generator.h"

#include <stddef.h>

#include "maxl/motion/fixed_point.h"
#include "maxl/readers/step_count.h"
#include "maxl/readers/step_times.h"

MAXL_StepGenerator::MAXL_StepGenerator(uint8_t stepPin, uint8_t dirPin, float stepsPerUnit, bool invertDirection)
    : begun_(false),
      direction_(0),
      steps_(0)
#if MAXL_STEP_TIMER
      ,
      lastLag_(0)
#endif
{
  this->stepPin().number = stepPin;
  this->stepPin().valid = false;
  this->dirPin().number = dirPin;
  this->dirPin().valid = false;
#if MAXL_STEP_TIMER
  channel_.invert = invertDirection;
#else
  invert_ = invertDirection;
#endif
  // s·2^16 = 2^32 / stepsPerUnit, at least 1 (so that stepping ends) and
  // below 2^47 (s below 2^31 units, 32 m per step).
  float q = stepsPerUnit > 0.0f ? 4294967296.0f / stepsPerUnit : 4294967296.0f;
  if (!(q >= 1.0f)) q = 1.0f;
  if (q > 1.4e14f) q = 1.4e14f;
  int64_t sq = (int64_t)q;
  sWhole_ = (int32_t)(sq >> 16);
  sFrac_ = (uint16_t)(sq & 0xFFFF);
  setSteps(0);
}

void MAXL_StepGenerator::begin() {
  if (begun_) return;
  begun_ = true;
  maxl_fw::hal::makeOutput(stepPin(), stepPin().number);
  maxl_fw::hal::makeOutput(dirPin(), dirPin().number);
  maxl_fw::hal::writePin(stepPin(), false);
}

// n = floor(p/s + 1/2): the n whose thresholds hold p, (n − 1/2)·s <= p <
// (n + 1/2)·s. From wherever the count is, with no step limit (a few jumps:
// see stepToward).
void MAXL_StepGenerator::reference(int32_t units) {
  walkToward(units, 0xFFFFFFFFul, 1);
  walkToward(units, 0xFFFFFFFFul, -1);
}

// (n + 1/2)·s in Q16, in 32-bit pieces: with s = S + F/2^16 and
// h = floor(s·2^16/2) = Hw + Hf/2^16 (Hw = S/2, Hf = (S mod 2)·2^15 + F/2),
//   (n·s + h)·2^16 = (n·S + Hw)·2^16 + n·F + Hf,
//   n·F = floor(n·F/2^16)·2^16 + (n·F mod 2^16),  floor(n·F/2^16) = mulhi16(n, F),
// and the low halves' sum carries into the whole part.
void MAXL_StepGenerator::setSteps(int32_t n) {
  steps_ = n;
  uint16_t hf = (uint16_t)(((uint16_t)(sWhole_ & 1) << 15) | (sFrac_ >> 1));
  uint16_t lo = (uint16_t)((uint16_t)n * sFrac_);
  uint16_t frac = (uint16_t)(lo + hf);
  upWhole_ = (int32_t)((uint32_t)n * (uint32_t)sWhole_ + (uint32_t)maxl_fw::mulhi16Cold(n, sFrac_) +
                       (uint32_t)(sWhole_ >> 1) + (frac < lo ? 1u : 0u));
  upFrac_ = frac;
}

#if MAXL_STEPPER_POLLING
// One pulse per step, from loop() (the thresholds have moved already).
void MAXL_StepGenerator::pulses(uint8_t count, int8_t direction) {
  if (!count) return;
  if (!begun_) begin();
  if (direction != direction_) {
    maxl_fw::hal::writePin(dirPin(), (direction > 0) != inverted());
    maxl_fw::hal::directionSetupWait();
    direction_ = direction;
  }
  while (count--) {
    maxl_fw::hal::writePin(stepPin(), true);
    maxl_fw::hal::stepPulseWait();
    maxl_fw::hal::writePin(stepPin(), false);
  }
}

bool MAXL_StepGenerator::moveTo(int32_t units) {
  const uint8_t budget = MAXL_MAX_STEPS_PER_EVALUATION;
  uint8_t n = stepsUpTo(units, budget);
  pulses(n, 1);
  if (!n) {
    n = stepsDownTo(units, budget);
    pulses(n, -1);
  }
  // all done unless the budget ran out (or a few more are due the other way:
  // not possible, the thresholds are half a step either side of n·s)
  return n < budget || (units < upCeil() && units >= downCeil());
}
#endif  // MAXL_STEPPER_POLLING

// ---------------------------------------------------------------- timed

// The window [0, w] µs; the position model m(t) = p0 + Δ·t/w, Δ = p1 − p0,
// held back by `lag` units in the direction of motion (the caller chooses
// the lag so that m is never ahead of the real path: stepper.h). Going up,
// step k is due when m reaches U_k = U_1 + (k−1)·s, U_1 = (n + 1/2)·s the
// next upper threshold; with m0 = m(0):
//
//   t_k = t_1 + (k−1)·I,   t_1 = (U_1 − m0)·r,   I = s·r,   r = w/Δ µs per unit
//
// In fixed point, with one 32-bit division per window:
//   R   = ceil(w·2^20 / Δ)        r in Q20; w <= 2^11, so w·2^20 <= 2^31
//   t_1 = x·R / 2^4  (Q16 µs)     x = U_1 − m0 = X + xf/2^16 (whole + fraction)
//       = X·R/2^4 + (xf·R/2^16)/2^4
//   I   = S·R/2^4 + (F·R/2^16)/2^4      s = S + F/2^16
// X·R stays in 32 bits because U_1 <= m1 makes X <= Δ, so X·R <= w·2^20 + Δ;
// S·R too when I is needed (2 steps or more: s <= Δ). xf·R/2^16 and F·R/2^16
// are mulhi16 (fixed_point.h). R is rounded up and the two floors are made good
// by + 2, so no time is early; R's rounding is at most 2^-20 µs per unit, so the
// times are late by at most |Δ|·2^-20 µs (0.06 µs for 1 mm in a window) plus
// 2^-16 µs per step. Thresholds the model already passed at 0 (the lag shrank,
// a segment's end snapped to p1, a jump) are a burst at 0. Going down is the
// mirror image, with the lower thresholds D_k = U_1 − k·s and "due when m < D".
#if MAXL_STEP_TIMER
#if defined(__AVR__) && !defined(MAXL_NO_ASM)
// timesR (step_times.h). avr-gcc's ABI: whole in r25..r22 (a3..a0), frac in
// r21:r20 (f1:f0), R in r19..r16 (b3..b0), the result in r25..r22. Uses the
// call-used r26, r27, r30, r31, r0 and r1 (cleared at the end), and r2 as a
// zero register (saved).
//   A = whole·R mod 2^32 in r31:r30:r27:r26: the byte products a_i·b_j with
//       i + j <= 3, each added at byte i + j (at byte 3 only its low byte).
//   B = floor(R·frac/2^16) in r25:r24:r23:r22: the products b_i·f_j, bytes 1
//       to 5 of the 48-bit product (byte 1, in r25 at first, only for its
//       carry into byte 2).
//   A/2^4 + B/2^4 (each a floor) = ((A & ~15) + (B & ~15))/2^4 on 33 bits:
//       the add's carry goes in with the first rotate, then the cleared low
//       nibbles rotate out zeros. Then + 2.
__attribute__((naked, noinline)) uint32_t maxl_fw::timesR(uint32_t, uint16_t, uint32_t) {
  __asm__ volatile(
      "push r2            \n\t"
      "clr  r2            \n\t"
      "mul  r22, r16      \n\t"  // A: a0·b0 at byte 0
      "movw r26, r0       \n\t"
      "clr  r30           \n\t"
      "clr  r31           \n\t"
      "mul  r22, r17      \n\t"  // a0·b1 at 1
      "add  r27, r0       \n\t"
      "adc  r30, r1       \n\t"
      "adc  r31, r2       \n\t"
      "mul  r23, r16      \n\t"  // a1·b0 at 1
      "add  r27, r0       \n\t"
      "adc  r30, r1       \n\t"
      "adc  r31, r2       \n\t"
      "mul  r22, r18      \n\t"  // a0·b2 at 2
      "add  r30, r0       \n\t"
      "adc  r31, r1       \n\t"
      "mul  r23, r17      \n\t"  // a1·b1 at 2
      "add  r30, r0       \n\t"
      "adc  r31, r1       \n\t"
      "mul  r24, r16      \n\t"  // a2·b0 at 2
      "add  r30, r0       \n\t"
      "adc  r31, r1       \n\t"
      "mul  r22, r19      \n\t"  // a0·b3, a1·b2, a2·b1, a3·b0 at 3 (low bytes)
      "add  r31, r0       \n\t"
      "mul  r23, r18      \n\t"
      "add  r31, r0       \n\t"
      "mul  r24, r17      \n\t"
      "add  r31, r0       \n\t"
      "mul  r25, r16      \n\t"
      "add  r31, r0       \n\t"
      "mul  r16, r20      \n\t"  // B: b0·f0 at 0 (byte 1 into r25)
      "mov  r25, r1       \n\t"
      "clr  r22           \n\t"
      "clr  r23           \n\t"
      "clr  r24           \n\t"
      "mul  r16, r21      \n\t"  // b0·f1 at 1
      "add  r25, r0       \n\t"
      "adc  r22, r1       \n\t"
      "adc  r23, r2       \n\t"
      "mul  r17, r20      \n\t"  // b1·f0 at 1
      "add  r25, r0       \n\t"
      "adc  r22, r1       \n\t"
      "adc  r23, r2       \n\t"
      "clr  r25           \n\t"  // byte 1 done; r25 is byte 5 now
      "mul  r17, r21      \n\t"  // b1·f1 at 2
      "add  r22, r0       \n\t"
      "adc  r23, r1       \n\t"
      "adc  r24, r2       \n\t"
      "mul  r18, r20      \n\t"  // b2·f0 at 2
      "add  r22, r0       \n\t"
      "adc  r23, r1       \n\t"
      "adc  r24, r2       \n\t"
      "mul  r18, r21      \n\t"  // b2·f1 at 3
      "add  r23, r0       \n\t"
      "adc  r24, r1       \n\t"
      "adc  r25, r2       \n\t"
      "mul  r19, r20      \n\t"  // b3·f0 at 3
      "add  r23, r0       \n\t"
      "adc  r24, r1       \n\t"
      "adc  r25, r2       \n\t"
      "mul  r19, r21      \n\t"  // b3·f1 at 4
      "add  r24, r0       \n\t"
      "adc  r25, r1       \n\t"
      "andi r26, 0xF0     \n\t"  // (A & ~15) + (B & ~15), carry out in C
      "andi r22, 0xF0     \n\t"
      "add  r22, r26      \n\t"
      "adc  r23, r27      \n\t"
      "adc  r24, r30      \n\t"
      "adc  r25, r31      \n\t"
      "ldi  r26, 4        \n\t"  // (ldi and dec leave C alone)
      "1:                 \n\t"
      "ror  r25           \n\t"
      "ror  r24           \n\t"
      "ror  r23           \n\t"
      "ror  r22           \n\t"
      "dec  r26           \n\t"
      "brne 1b            \n\t"
      "subi r22, 0xFE     \n\t"  // + 2
      "sbci r23, 0xFF     \n\t"
      "sbci r24, 0xFF     \n\t"
      "sbci r25, 0xFF     \n\t"
      "clr  r1            \n\t"
      "pop  r2            \n\t"
      "ret                \n\t");
}
#endif
namespace {
__attribute__((noinline)) void burstRun(MAXL_StepWindow& out, uint8_t count, bool backward) {
  MAXL_StepWindow::Run& r = out.run[out.runs++];
  r.first = 0;
  r.interval = 0;
  r.count = count;
  r.backward = backward;
}
}  // namespace
#endif

// Moves the count (and its thresholds) up while `units` is at or past the
// next upper threshold (direction +1), or down while it is below the lower
// one (−1), at most `max` steps; returns how many.
//
// Far from the threshold, many steps go in one jump. Going up, with
// d = units − ceil(U_1) >= 0 and k = floor(d / (S + 1)), the thresholds
// U_1 .. U_(k+1) are all crossed, because s < S + 1 gives
//   ceil(U_(k+1)) = ceil(U_1 + k·s) <= ceil(U_1) + ceil(k·s) <= ceil(U_1) + k·(S + 1) <= units.
// Going down, with d = ceil(D_1) − 1 − units >= 0, likewise
//   ceil(D_(k+1)) = ceil(D_1 − k·s) >= ceil(D_1) − ceil(k·s) >= units + 1.
// So k + 1 steps go at once (setSteps keeps the thresholds exact), and the
// next pass starts from what is left, at most about d/(S·(S + 1)) + 1 steps
// (one or two at 80 steps/mm). A pass costs a 32-bit division and setSteps
// (~900 cycles on an AVR).
//
// First, where the numbers allow (countJumpFits: within 8 m, steps under
// 128 mm) and at most 128 steps are due, the whole count in one pass:
// countJump (step_count.h; AVR assembly, ~250 cycles) finds the same count
// and the same next threshold exactly, by a division with a 7-bit quotient.
// A window's count and its burst check go that way; the walk below is left
// for the rest (a reference far away, a count past `max`), where speed matters
// less than flash.
//
// On the AVR, stepToward is a few instructions of assembly that first ask
// whether a step is due at all (the ceilings' compare below), before any
// register is saved: a window's burst check finds none due almost always
// (keptLag), and the C count's register saves cost more than the count then.
inline __attribute__((always_inline)) uint8_t MAXL_StepGenerator::countToward(int32_t units, uint8_t max,
                                                                              int8_t direction) {
  if (maxl_fw::countJumpFits(units, upWhole_, sWhole_)) {
    uint32_t whole = (uint32_t)upWhole_;
    uint16_t frac = upFrac_;
    uint8_t k = maxl_fw::countJump(units, (uint32_t)sWhole_, sFrac_, whole, frac, direction > 0);
    if (k <= max && k != maxl_fw::COUNT_NOT_HERE) {
      if (k) {
        upWhole_ = (int32_t)whole;
        upFrac_ = frac;
        steps_ = (int32_t)(direction > 0 ? (uint32_t)steps_ + k : (uint32_t)steps_ - k);
      }
      return k;
    }
  }
  return (uint8_t)walkToward(units, max, direction);
}

#if defined(__AVR__) && !defined(MAXL_NO_ASM)
extern "C" __attribute__((used, noinline)) uint8_t maxl_stepTowardDue(MAXL_StepGenerator* generator, int32_t units,
                                                                       uint8_t max, int8_t direction) {
  return generator->countToward(units, max, direction);
}

// The generator in r25:r24 (kept in Z), units in r23..r20, max in r18, direction in
// r16 (all left as they are for maxl_stepTowardDue). None due: return 0.
//   up:   due when units >= ceil(U_1) = upWhole + (upFrac != 0)        (upCeil)
//   down: due when units <  ceil(D_1) = upWhole − sWhole + (upFrac > sFrac) (downCeil)
// Each ceiling is built in r27..r24 (the carry first: `cp r1, x` sets C when
// x != 0, `cp sFrac, upFrac` when sFrac < upFrac; the loads leave C alone),
// then one signed compare, as the C forms (walkToward's first test) make it.
extern "C" __attribute__((naked, noinline)) uint8_t maxl_stepToward(MAXL_StepGenerator*, int32_t, uint8_t, int8_t) {
  __asm__ volatile(
      "movw r30, r24           \n\t"
      "ldd  r24, Z+%[uf]       \n\t"
      "ldd  r25, Z+%[uf]+1     \n\t"
      "sbrc r16, 7             \n\t"
      "rjmp 2f                 \n\t"
      "or   r24, r25           \n\t"  // up: C = (upFrac != 0)
      "cp   r1, r24            \n\t"
      "rjmp 3f                 \n\t"
      "2:                      \n\t"
      "ldd  r0, Z+%[sf]        \n\t"  // down: C = (sFrac < upFrac)
      "cp   r0, r24            \n\t"
      "ldd  r0, Z+%[sf]+1      \n\t"
      "cpc  r0, r25            \n\t"
      "3:                      \n\t"
      "ldd  r24, Z+%[uw]       \n\t"  // upWhole + C
      "ldd  r25, Z+%[uw]+1     \n\t"
      "ldd  r26, Z+%[uw]+2     \n\t"
      "ldd  r27, Z+%[uw]+3     \n\t"
      "adc  r24, r1            \n\t"
      "adc  r25, r1            \n\t"
      "adc  r26, r1            \n\t"
      "adc  r27, r1            \n\t"
      "sbrs r16, 7             \n\t"
      "rjmp 4f                 \n\t"
      "ldd  r0, Z+%[sw]        \n\t"  // down: − sWhole
      "sub  r24, r0            \n\t"
      "ldd  r0, Z+%[sw]+1      \n\t"
      "sbc  r25, r0            \n\t"
      "ldd  r0, Z+%[sw]+2      \n\t"
      "sbc  r26, r0            \n\t"
      "ldd  r0, Z+%[sw]+3      \n\t"
      "sbc  r27, r0            \n\t"
      "4:                      \n\t"
      "cp   r20, r24           \n\t"  // units vs the ceiling, signed
      "cpc  r21, r25           \n\t"
      "cpc  r22, r26           \n\t"
      "cpc  r23, r27           \n\t"
      "movw r24, r30           \n\t"  // this again (movw leaves the flags)
      "brlt 5f                 \n\t"
      "sbrs r16, 7             \n\t"  // units >= ceiling: due going up
      "jmp  maxl_stepTowardDue \n\t"
      "rjmp 6f                 \n\t"
      "5:                      \n\t"
      "sbrc r16, 7             \n\t"  // units < ceiling: due going down
      "jmp  maxl_stepTowardDue \n\t"
      "6:                      \n\t"
      "ldi  r24, 0             \n\t"
      "ret                     \n\t"
      :
      : [uw] "n"(offsetof(MAXL_StepGenerator, upWhole_)), [uf] "n"(offsetof(MAXL_StepGenerator, upFrac_)),
        [sw] "n"(offsetof(MAXL_StepGenerator, sWhole_)), [sf] "n"(offsetof(MAXL_StepGenerator, sFrac_)));
}
#else
uint8_t MAXL_StepGenerator::stepToward(int32_t units, uint8_t max, int8_t direction) {
  return countToward(units, max, direction);
}
#endif

// stepToward's general way (out of line: the one-pass count above then needs
// few registers saved), and reference()'s, with no step limit.
__attribute__((noinline)) uint32_t MAXL_StepGenerator::walkToward(int32_t units, uint32_t max, int8_t direction) {
  uint32_t n = 0;
  const uint32_t s1 = (uint32_t)sWhole_ + 1u;
  const bool up = direction > 0;
  while (n < max) {
    // up: due while units >= ceil(U_1), d = units − ceil(U_1);
    // down: due while units < ceil(D_1), d = ceil(D_1) − 1 − units = ~(units − ceil(D_1))
    int32_t edge = up ? upCeil() : downCeil();
    if ((units < edge) == up) break;
    uint32_t d = (uint32_t)units - (uint32_t)edge;
    if (!up) d = ~d;
    uint32_t k = d / s1 + 1u;
    if (k > max - n) k = max - n;
    // in u32: a count past ±2^31 (a position the step size cannot count to)
    // wraps like the thresholds do, without undefined behaviour
    setSteps((int32_t)(up ? (uint32_t)steps_ + k : (uint32_t)steps_ - k));
    n += k;
  }
  return n;
}

#if MAXL_STEP_TIMER
// The lag for a window from p0 that asks for `lag`. Where the lag shrank since
// the last window (a window cut short at a piece's end has a smaller bend, a
// speed-up ended), the thresholds between the last window's m1 and this m0
// would be a burst at 0, a run of its own, and the ring (MAXL_STEP_RING runs)
// would then hold a window less of lead. Instead the lag stays just large
// enough that none is due at 0: m0 below the next upper threshold going up
// (m0 < ceil(U_1): lag = p0 − ceil(U_1) + 1), at or above the next lower one
// going down (m0 >= ceil(D_1): lag = ceil(D_1) − p0). (From the floors, as this
// did at first, the lag came out a unit too large wherever the threshold has a
// fraction: past the last window's by one where that window's m1 was just below
// the threshold, so refused, and the window began with a burst after all.)
// Only between the asked lag and the last window's, so no step is earlier than
// with the asked lag, and none later than the last window held it; the extra
// shrinks as the steps go by (the next window's thresholds are past this one's
// m1). A jump (p0 far past the thresholds) stays a burst.
inline int32_t MAXL_StepGenerator::keptLag(bool forward, int32_t p0, int32_t lag) {
  if (lag < lastLag_) {
    int32_t keep = forward ? (int32_t)((uint32_t)p0 - (uint32_t)upCeil() + 1u) : (int32_t)((uint32_t)downCeil() - (uint32_t)p0);
    if (keep > lag && keep <= lastLag_) lag = keep;
  }
  lastLag_ = lag;
  return lag;
}

void MAXL_StepGenerator::planWindow(uint16_t w, int32_t p0, int32_t p1, int32_t lag, MAXL_StepWindow& out) {
  out.runs = 0;
  int32_t delta = (int32_t)((uint32_t)p1 - (uint32_t)p0);
  const uint8_t maxRun = maxl_fw::StepChannel::MAX_RUN;
  if (w > 2048) w = 2048;
  if (delta == 0) {
    // at rest: catch up to the step p0 rounds to, either way, at once
    lastLag_ = 0;
    uint8_t n = stepsUpTo(p0, maxRun);
    if (n) return burstRun(out, n, false);
    n = stepsDownTo(p0, maxRun);
    if (n) burstRun(out, n, true);
    return;
  }
  bool forward = delta > 0;
  uint32_t dist = forward ? (uint32_t)delta : (uint32_t)0 - (uint32_t)delta;
  lag = keptLag(forward, p0, lag);
  int32_t back = forward ? -lag : lag;
  int32_t m0 = (int32_t)((uint32_t)p0 + (uint32_t)back);
  int32_t m1 = (int32_t)((uint32_t)p1 + (uint32_t)back);
  uint8_t burst, n;
  uint32_t whole;  // x = U_1 − m0 (or m0 − D_1) = whole + frac/2^16
  uint16_t frac;
  if (forward) {
    burst = stepsUpTo(m0, maxRun);
    whole = (uint32_t)upWhole_ - (uint32_t)m0;
    frac = upFrac_;
    n = stepsUpTo(m1, (uint8_t)(maxRun - burst));
  } else {
    burst = stepsDownTo(m0, maxRun);
    // D_1 = (upWhole − S) + (upFrac − F)/2^16, borrowing; m0 − D_1 likewise
    uint16_t dFrac = (uint16_t)(upFrac_ - sFrac_);
    uint32_t dWhole = (uint32_t)upWhole_ - (uint32_t)sWhole_ - (upFrac_ < sFrac_ ? 1u : 0u);
    whole = (uint32_t)m0 - dWhole - (dFrac ? 1u : 0u);
    frac = (uint16_t)(0u - dFrac);
    n = stepsDownTo(m1, (uint8_t)(maxRun - burst));
  }
  if (burst) burstRun(out, burst, !forward);
  if (!n) return;
  uint32_t r = maxl_fw::divideWindow(((uint32_t)w << 20) + dist - 1, dist);
  if (r > 0x7FFFFFFFul) r = 0x7FFFFFFFul;  // w = 2^11 and Δ = 1: one unit, one step at most
  MAXL_StepWindow::Run& run = out.run[out.runs++];
  run.first = maxl_fw::timesR(whole, frac, r);
  run.interval = n > 1 ? maxl_fw::timesR((uint32_t)sWhole_, sFrac_, r) : 0;
  run.count = n;
  run.backward = !forward;
}
#endif  // MAXL_STEP_TIMER
