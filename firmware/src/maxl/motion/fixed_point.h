// The evaluation hot path: one position track's value at a time, in fixed point.
//
// Within one phase of a segment (protocol §5) every position track is a
// quadratic in time. We keep it, per track, relative to a "chunk" start:
//
//   p(x) = P + B·x/2^16 + C·x²/2^32           x = µs since the chunk start, x < 2^16
//
//   P  i32  position at the chunk start, in position units (2^-16 mm)
//   B  i32  velocity, units/µs in Q16.16      (|v| < 2^15 units/µs = 500 m/s)
//   C  i32  half the acceleration, units/µs² in Q0.32
//
// and evaluate it Horner-style with two 32×16-bit multiplies:
//
//   W = B + floor(C·x / 2^16)            (the mean velocity over [0, x], Q16.16)
//   p = P + floor(W·x / 2^16)
//
// Each floor drops less than one unit of its result, so p is within 2 units
// (31 nm) of the exact quadratic; the error does not accumulate because P, B
// and C are only ever moved exactly (below) or re-set from the segment.
//
// Chunks are 2^16 µs long so that moving to the next one is exact integer
// arithmetic: with X = 2^16,
//   p(X + y) = P + B·(X+y)/2^16 + C·(X+y)²/2^32
//            = (P + B + C) + (B + 2C)·y/2^16 + C·y²/2^32
// so P' = P + B + C, B' = B + 2C, C' = C: three additions, no rounding.
//
// Moving to the next phase at x_e (not a power of two) uses the same formulas,
// with the floors: P' = p(x_e), B' = B + 2·floor(C·x_e/2^16), C' = the new
// phase's. That costs at most 2 units in P and 2^-15 units/µs in B per phase
// boundary, and the segment's end snaps to its exact p1 anyway.
#ifndef MAXL_MOTION_FIXED_POINT_H
#define MAXL_MOTION_FIXED_POINT_H

#include <stdint.h>

namespace maxl_fw {

// The hot path must be inlined even under the Arduino build's -Os.
#define MAXL_HOT inline __attribute__((always_inline))

// floor(a·x / 2^16) for a signed 32-bit a and an unsigned 16-bit x. The
// product fits in 48 bits, so the result fits in 32.
//
// Portable form: split a = h·2^16 + l (h signed, l unsigned 16-bit); then
// a·x/2^16 = h·x + l·x/2^16, and since h·x is an integer,
// floor(a·x/2^16) = h·x + floor(l·x/2^16), which is exact.
MAXL_HOT int32_t mulhi16Portable(int32_t a, uint16_t x) {
  int32_t h = (int32_t)(int16_t)((uint32_t)a >> 16);
  uint32_t l = (uint16_t)a;
  return (int32_t)((uint32_t)(h * (int32_t)x) + ((l * x) >> 16));
}

#if defined(__AVR__) && !defined(MAXL_NO_ASM)
// The same on AVR's 8×8 hardware multiplier: avr-gcc 5.4 turns the portable
// form into four full 32×32 multiplies (~450 cycles); this is eight MULs.
// The 48-bit product is accumulated in r18..r23 (bytes 0..5); bytes 2..5
// are the result. a = a3:a2:a1:a0 (a3 signed), x = x1:x0.
MAXL_HOT int32_t mulhi16(int32_t a, uint16_t x) {
  int32_t result;
  uint8_t b0, b1, zero;
  __asm__(
      "clr %[z]                \n\t"
      // a0·x0 -> bytes 0,1
      "mul %A[a], %A[x]        \n\t"
      "mov %[b0], r0           \n\t"
      "mov %[b1], r1           \n\t"
      "clr %A[r]               \n\t"
      "clr %B[r]               \n\t"
      "clr %C[r]               \n\t"
      "clr %D[r]               \n\t"
      // a0·x1 -> bytes 1,2
      "mul %A[a], %B[x]        \n\t"
      "add %[b1], r0           \n\t"
      "adc %A[r], r1           \n\t"
      "adc %B[r], %[z]         \n\t"
      // a1·x0 -> bytes 1,2
      "mul %B[a], %A[x]        \n\t"
      "add %[b1], r0           \n\t"
      "adc %A[r], r1           \n\t"
      "adc %B[r], %[z]         \n\t"
      // a1·x1 -> bytes 2,3
      "mul %B[a], %B[x]        \n\t"
      "add %A[r], r0           \n\t"
      "adc %B[r], r1           \n\t"
      "adc %C[r], %[z]         \n\t"
      // a2·x0 -> bytes 2,3
      "mul %C[a], %A[x]        \n\t"
      "add %A[r], r0           \n\t"
      "adc %B[r], r1           \n\t"
      "adc %C[r], %[z]         \n\t"
      // a2·x1 -> bytes 3,4
      "mul %C[a], %B[x]        \n\t"
      "add %B[r], r0           \n\t"
      "adc %C[r], r1           \n\t"
      "adc %D[r], %[z]         \n\t"
      // a3·x0 (signed × unsigned) -> bytes 3,4, sign-extended into byte 5
      "mulsu %D[a], %A[x]      \n\t"
      "sbc %[b0], %[b0]        \n\t"  // b0 = 0xFF if the product is negative (C = bit 15), else 0
      "add %B[r], r0           \n\t"
      "adc %C[r], r1           \n\t"
      "adc %D[r], %[b0]        \n\t"
      // a3·x1 (signed × unsigned) -> bytes 4,5
      "mulsu %D[a], %B[x]      \n\t"
      "add %C[r], r0           \n\t"
      "adc %D[r], r1           \n\t"
      "clr r1                  \n\t"
      : [r] "=&r"(result), [b0] "=&r"(b0), [b1] "=&r"(b1), [z] "=&r"(zero)
      : [a] "a"(a), [x] "a"(x)
      : "r0", "r1");
  return result;
}
#else
MAXL_HOT int32_t mulhi16(int32_t a, uint16_t x) { return mulhi16Portable(a, x); }
#endif

// The same, out of line, for code off the hot path (step planning): one
// copy of the multiply instead of one per use (flash is short on an Uno).
int32_t mulhi16Cold(int32_t a, uint16_t x);

// One position track inside the current phase (see the top of this file).
struct FixedTrack {
  int32_t P;
  int32_t B;
  int32_t C;

  // Position x µs after the chunk start, x < 2^16.
  MAXL_HOT int32_t at(uint16_t x) const {
    int32_t w = (int32_t)((uint32_t)B + (uint32_t)mulhi16(C, x));
    return (int32_t)((uint32_t)P + (uint32_t)mulhi16(w, x));
  }
  // Moves the chunk start 2^16 µs on, exactly.
  void nextChunk() {
    P = (int32_t)((uint32_t)P + (uint32_t)B + (uint32_t)C);
    B = (int32_t)((uint32_t)B + 2u * (uint32_t)C);
  }
  // Moves the chunk start to x µs on (x < 2^16), keeping position and
  // velocity continuous; C stays as it is until the caller sets the next phase's.
  void advance(uint16_t x) {
    int32_t half = mulhi16(C, x);
    P = (int32_t)((uint32_t)P + (uint32_t)mulhi16((int32_t)((uint32_t)B + (uint32_t)half), x));
    B = (int32_t)((uint32_t)B + 2u * (uint32_t)half);
  }
};

}  // namespace maxl_fw

#endif
