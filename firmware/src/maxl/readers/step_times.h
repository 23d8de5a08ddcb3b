// A window's step times from its µs per unit (step_generator.cpp's planWindow):
// with R = ceil(w·2^20/Δ) (r = w/Δ µs per unit in Q20) and a distance
// x = whole + frac/2^16 units, the time x·r in Q16 µs, rounded up:
//
//   timesR(whole, frac, R) = (whole·R mod 2^32)/2^4 + (R·frac/2^16)/2^4 + 2
//
// (each / a floor; the + 2 makes the two floors good, so no time is early;
// step_generator.cpp has the derivation and why whole·R fits 32 bits where
// it is used). Twice a window and stepper (the first step's time and the
// interval), so on the AVR it is hand-written: avr-gcc's form calls
// __mulsi3 and mulhi16Cold, shifts twice in loops and saves 14 registers
// (~273 cycles a call); the assembly multiplies in place and saves one
// (~120 cycles). R < 2^31 (planWindow clamps it).
#ifndef MAXL_READERS_STEP_TIMES_H
#define MAXL_READERS_STEP_TIMES_H

#include <stdint.h>

namespace maxl_fw {

// Portable form, as the formula reads (R < 2^31: R·frac/2^16 as unsigned).
inline uint32_t timesRPortable(uint32_t whole, uint16_t frac, uint32_t r) {
  return ((whole * r) >> 4) + ((uint32_t)(((uint64_t)r * frac) >> 16) >> 4) + 2;
}

#if defined(__AVR__) && !defined(MAXL_NO_ASM)
// AVR assembly (step_generator.cpp); checked against timesRPortable in simavr
// by bench/StepCountCheck.
uint32_t timesR(uint32_t whole, uint16_t frac, uint32_t r);
#else
inline uint32_t timesR(uint32_t whole, uint16_t frac, uint32_t r) { return timesRPortable(whole, frac, r); }
#endif

}  // namespace maxl_fw

#endif
