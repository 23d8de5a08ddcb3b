// A stepper's count moved to a position in one pass: how many step
// thresholds lie between the next one and the position, and the threshold
// after them, by one short division (a 7-bit quotient) and no multiply.
//
// In Q16 units (2^-16 of a position unit), with the step size s ≥ 1, the next
// upper threshold U = (n + 1/2)·s (MAXL_StepGenerator's upWhole_:upFrac_) and
// the position M = m·2^16 (m whole units):
//
// Up. Threshold j ≥ 1 is U_j = U + (j − 1)·s, crossed when m ≥ ceil(U_j),
// i.e. M ≥ U_j (m is whole). With d = M − U ≥ 0 the crossed ones are
// j − 1 ≤ d/s, so k = q + 1 steps, q = floor(d/s), r = d − q·s, and the next
// threshold is U + k·s = (U + q·s) + s = (M − r) + s.
//
// Down. Threshold j ≥ 1 is D_j = U − j·s, crossed when m < ceil(D_j), i.e.
// M < D_j, j·s < U − M = e, j·s ≤ e − 1. With d = e − 1 − s ≥ 0 that is
// k = floor((e − 1)/s) = q + 1 steps (q, r of d as above), and the next upper
// threshold is U − k·s = U − s − (d − r) = M + 1 + r.
//
// d < 0: no step is due (k = 0). q is found by long division with a 7-bit
// quotient, so only for d < 128·s (k ≤ 128); past that the answer is 255,
// "not counted here" (the caller walks the general way: step_generator.cpp's
// walkToward).
//
// The domain (checked by the caller, countJumpFits): |m| and |upWhole| under
// 2^29 (8 m of travel) and the step's whole units S under 2^23, so every
// value below fits a signed 48-bit number: |M|, |U| < 2^45, |d| < 2^46 + 2^39,
// s·2^8 < 2^47, and the thresholds reached stay within int32 (so this count
// is the one walkToward's signed compares find, bit for bit).
#ifndef MAXL_READERS_STEP_COUNT_H
#define MAXL_READERS_STEP_COUNT_H

#include <stdint.h>

namespace maxl_fw {

const uint8_t COUNT_NOT_HERE = 255;

// |x| < 2^29 (−2^29 ≤ x < 2^29): x + 2^29 < 2^30, which only its top byte decides.
inline bool under2to29(int32_t x) { return (uint8_t)((uint8_t)((uint32_t)x >> 24) + 0x20u) < 0x40u; }
inline bool countJumpFits(int32_t m, int32_t upWhole, int32_t sWhole) {
  return under2to29(m) && under2to29(upWhole) && (uint16_t)((uint32_t)sWhole >> 16) < 0x80u;  // 0 ≤ S < 2^23
}

// The count k (0..128, or COUNT_NOT_HERE) from the next upper threshold
// upWhole + upFrac/2^16 to m, going up (`up`) or down, with the step
// s = sWhole + sFrac/2^16; moves upWhole/upFrac on to the next threshold when
// 1 ≤ k ≤ 128 (otherwise they hold nothing useful). In the domain above.
// Portable form: 64-bit arithmetic, as the derivation reads.
inline uint8_t countJumpPortable(int32_t m, uint32_t sWhole, uint16_t sFrac, uint32_t& upWhole, uint16_t& upFrac,
                                 bool up) {
  const int64_t s = (int64_t)(((uint64_t)sWhole << 16) | sFrac);
  const int64_t U = (int64_t)(int32_t)upWhole * 65536 + upFrac;
  const int64_t M = (int64_t)m * 65536;
  const int64_t d = up ? M - U : U - M - 1 - s;
  if (d < 0) return 0;
  if (d >= s * 128) return COUNT_NOT_HERE;
  const int64_t q = d / s, r = d - q * s;
  const int64_t next = up ? M - r + s : M + 1 + r;
  upWhole = (uint32_t)(uint64_t)(next >> 16);
  upFrac = (uint16_t)(uint64_t)next;
  return (uint8_t)(q + 1);
}

#if defined(__AVR__) && !defined(MAXL_NO_ASM)
// The same in AVR assembly (avr-gcc turns the 48-bit arithmetic into 64-bit
// library calls). U is worked on in place in u5..u0 (upWhole:upFrac, the
// caller's copies), s in s5..s0 (sWhole:sFrac, S's top byte 0); ~250 cycles.
//   e = U − M                                   (M's low 16 bits are 0)
//   up: d = −e;  down: d = e − s − 1            (com sets C, so +1 is an adc)
//   d < 0: k = 0
//   T = s·2^8 (by moving bytes)
//   8 times: T >>= 1; if d ≥ T: d −= T. The compare's carry is the quotient
//     bit inverted, on both paths (no borrow after the subtraction); it is
//     rotated into q, which starts at 1: the 1 comes out after 8 bits.
//   q = ~q; q ≥ 128 (its first bit, d ≥ s·2^7): COUNT_NOT_HERE;
//   k = q + 1; T = s again.
//   up: U' = (s − r) + M;  down: U' = r + 1 + M (r = d, now the remainder)
inline uint8_t countJump(int32_t m, uint32_t sWhole, uint16_t sFrac, uint32_t& upWhole, uint16_t& upFrac, bool up) {
  uint8_t k;
  __asm__(
      "sub  %A[uw], %A[m]      \n\t"  // e = U − M
      "sbc  %B[uw], %B[m]      \n\t"
      "sbc  %C[uw], %C[m]      \n\t"
      "sbc  %D[uw], %D[m]      \n\t"
      "tst  %[up]              \n\t"
      "breq 1f                 \n\t"
      "com  %A[uf]             \n\t"  // up: d = −e = ~e + 1
      "com  %B[uf]             \n\t"
      "com  %A[uw]             \n\t"
      "com  %B[uw]             \n\t"
      "com  %C[uw]             \n\t"
      "com  %D[uw]             \n\t"  // C = 1
      "adc  %A[uf], __zero_reg__ \n\t"
      "adc  %B[uf], __zero_reg__ \n\t"
      "adc  %A[uw], __zero_reg__ \n\t"
      "adc  %B[uw], __zero_reg__ \n\t"
      "adc  %C[uw], __zero_reg__ \n\t"
      "adc  %D[uw], __zero_reg__ \n\t"
      "rjmp 2f                 \n\t"
      "1:                      \n\t"
      "sec                     \n\t"  // down: d = e − s − 1
      "sbc  %A[uf], %A[sf]     \n\t"
      "sbc  %B[uf], %B[sf]     \n\t"
      "sbc  %A[uw], %A[sw]     \n\t"
      "sbc  %B[uw], %B[sw]     \n\t"
      "sbc  %C[uw], %C[sw]     \n\t"
      "sbc  %D[uw], %D[sw]     \n\t"
      "2:                      \n\t"
      "clr  %[k]               \n\t"
      "sbrc %D[uw], 7          \n\t"  // d < 0: k = 0
      "rjmp 9f                 \n\t"
      "mov  %D[sw], %C[sw]     \n\t"  // T = s·2^8 (S's top byte is 0)
      "mov  %C[sw], %B[sw]     \n\t"
      "mov  %B[sw], %A[sw]     \n\t"
      "mov  %A[sw], %B[sf]     \n\t"
      "mov  %B[sf], %A[sf]     \n\t"
      "clr  %A[sf]             \n\t"
      "inc  %[k]               \n\t"  // the marker bit
      "4:                      \n\t"
      "lsr  %D[sw]             \n\t"  // T >>= 1
      "ror  %C[sw]             \n\t"
      "ror  %B[sw]             \n\t"
      "ror  %A[sw]             \n\t"
      "ror  %B[sf]             \n\t"
      "ror  %A[sf]             \n\t"
      "cp   %A[uf], %A[sf]     \n\t"
      "cpc  %B[uf], %B[sf]     \n\t"
      "cpc  %A[uw], %A[sw]     \n\t"
      "cpc  %B[uw], %B[sw]     \n\t"
      "cpc  %C[uw], %C[sw]     \n\t"
      "cpc  %D[uw], %D[sw]     \n\t"
      "brlo 5f                 \n\t"  // C = 1: bit 0
      "sub  %A[uf], %A[sf]     \n\t"  // d −= T, C = 0: bit 1
      "sbc  %B[uf], %B[sf]     \n\t"
      "sbc  %A[uw], %A[sw]     \n\t"
      "sbc  %B[uw], %B[sw]     \n\t"
      "sbc  %C[uw], %C[sw]     \n\t"
      "sbc  %D[uw], %D[sw]     \n\t"
      "5:                      \n\t"
      "rol  %[k]               \n\t"
      "brcc 4b                 \n\t"  // the marker out after 8 bits
      "com  %[k]               \n\t"  // the quotient
      "sbrc %[k], 7            \n\t"  // q >= 128: more than 128 steps
      "rjmp 8f                 \n\t"
      "inc  %[k]               \n\t"  // k = q + 1
      "tst  %[up]              \n\t"
      "breq 6f                 \n\t"
      "sub  %A[sf], %A[uf]     \n\t"  // up: U' = (s − r) + M
      "sbc  %B[sf], %B[uf]     \n\t"
      "sbc  %A[sw], %A[uw]     \n\t"
      "sbc  %B[sw], %B[uw]     \n\t"
      "sbc  %C[sw], %C[uw]     \n\t"
      "sbc  %D[sw], %D[uw]     \n\t"
      "add  %A[sw], %A[m]      \n\t"
      "adc  %B[sw], %B[m]      \n\t"
      "adc  %C[sw], %C[m]      \n\t"
      "adc  %D[sw], %D[m]      \n\t"
      "movw %A[uf], %A[sf]     \n\t"  // (avr-gcc puts multi-byte values at even registers)
      "movw %A[uw], %A[sw]     \n\t"
      "movw %C[uw], %C[sw]     \n\t"
      "rjmp 9f                 \n\t"
      "6:                      \n\t"
      "sec                     \n\t"  // down: U' = r + 1 + M
      "adc  %A[uf], __zero_reg__ \n\t"
      "adc  %B[uf], __zero_reg__ \n\t"
      "adc  %A[uw], %A[m]      \n\t"
      "adc  %B[uw], %B[m]      \n\t"
      "adc  %C[uw], %C[m]      \n\t"
      "adc  %D[uw], %D[m]      \n\t"
      "rjmp 9f                 \n\t"
      "8:                      \n\t"
      "clr  %[k]               \n\t"  // COUNT_NOT_HERE
      "dec  %[k]               \n\t"
      "9:                      \n\t"
      : [k] "=&r"(k), [uw] "+r"(upWhole), [uf] "+r"(upFrac), [sw] "+r"(sWhole), [sf] "+r"(sFrac)
      : [m] "r"(m), [up] "r"((uint8_t)up));
  return k;
}
#else
inline uint8_t countJump(int32_t m, uint32_t sWhole, uint16_t sFrac, uint32_t& upWhole, uint16_t& upFrac, bool up) {
  return countJumpPortable(m, sWhole, sFrac, upWhole, upFrac, up);
}
#endif


// floor(n / d) for d ≥ 1, exactly as C's n / d: a window's µs per unit
// (step_generator.cpp's R). libgcc's __udivmodsi4 takes 32 rounds of shift
// and subtract (~600 cycles); the leading rounds only gather n's top bytes
// while they are below d (their quotient bits are 0), so here whole bytes
// of n go at once while (remainder·2^8 + n's next byte) < d, and the rounds
// are only those of the quotient's significant bytes (R below 2^16 after
// the first byte: ~350 cycles for 80 steps/mm at 20 kHz).
#if defined(__AVR__) && !defined(MAXL_NO_ASM)
inline uint32_t divideWindow(uint32_t n, uint32_t d) {
  uint32_t rem;
  uint8_t count;
  __asm__(
      "clr  %A[rem]            \n\t"
      "clr  %B[rem]            \n\t"
      "movw %C[rem], %A[rem]   \n\t"
      "ldi  %[c], 32           \n\t"
      "1:                      \n\t"  // (rem·2^8 + n's top byte) < d: 8 quotient bits 0
      "cp   %D[n], %A[d]       \n\t"  // (rem's top byte is still 0 here)
      "cpc  %A[rem], %B[d]     \n\t"
      "cpc  %B[rem], %C[d]     \n\t"
      "cpc  %C[rem], %D[d]     \n\t"
      "brsh 2f                 \n\t"
      "mov  %D[rem], %C[rem]   \n\t"
      "mov  %C[rem], %B[rem]   \n\t"
      "mov  %B[rem], %A[rem]   \n\t"
      "mov  %A[rem], %D[n]     \n\t"
      "mov  %D[n], %C[n]       \n\t"
      "mov  %C[n], %B[n]       \n\t"
      "mov  %B[n], %A[n]       \n\t"
      "clr  %A[n]              \n\t"
      "subi %[c], 8            \n\t"
      "brne 1b                 \n\t"
      "rjmp 4f                 \n\t"  // n < d: 0
      "2:                      \n\t"  // one bit a round: n's top bit into rem, the quotient bit into n's bottom
      "lsl  %A[n]              \n\t"
      "rol  %B[n]              \n\t"
      "rol  %C[n]              \n\t"
      "rol  %D[n]              \n\t"
      "rol  %A[rem]            \n\t"
      "rol  %B[rem]            \n\t"
      "rol  %C[rem]            \n\t"
      "rol  %D[rem]            \n\t"  // rem < 2^31 before it (a prefix of n's 32 bits): no carry lost
      "cp   %A[rem], %A[d]     \n\t"
      "cpc  %B[rem], %B[d]     \n\t"
      "cpc  %C[rem], %C[d]     \n\t"
      "cpc  %D[rem], %D[d]     \n\t"
      "brlo 3f                 \n\t"
      "sub  %A[rem], %A[d]     \n\t"
      "sbc  %B[rem], %B[d]     \n\t"
      "sbc  %C[rem], %C[d]     \n\t"
      "sbc  %D[rem], %D[d]     \n\t"
      "inc  %A[n]              \n\t"  // bit 0 is 0 after the shift
      "3:                      \n\t"
      "dec  %[c]               \n\t"
      "brne 2b                 \n\t"
      "4:                      \n\t"
      : [n] "+r"(n), [rem] "=&r"(rem), [c] "=&d"(count)
      : [d] "r"(d));
  return n;
}
#else
inline uint32_t divideWindow(uint32_t n, uint32_t d) { return n / d; }
#endif

}  // namespace maxl_fw

#endif
