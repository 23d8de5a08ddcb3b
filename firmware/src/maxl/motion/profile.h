// Float maths done once per segment, when its timing arrives or when braking
// starts: never in the per-evaluation hot path (see fixed_point.h for that).
// Floats are IEEE singles on every target (AVR's double is one too), so the
// host tests exercise the same arithmetic the Uno runs.
#ifndef MAXL_MOTION_PROFILE_H
#define MAXL_MOTION_PROFILE_H

#include <stdint.h>

#include "maxl/motion/segment.h"

namespace maxl_fw {

// Fixed-point scales of fixed_point.h, per µs: Q16.16 velocity and Q0.32 half
// acceleration. 1 unit = 2^-16 mm.
const float UNITS_PER_MM = 65536.0f;
const float B_SCALE = 65536.0f * 1e-6f;          // (units/s) -> (units/µs)·2^16
const float C_SCALE = 4294967296.0f * 1e-12f;    // (units/s²) -> (units/µs²)·2^32
// Coefficients are kept below 2^30 so that sums of two never overflow 32 bits.
const float FIXED_LIMIT = 1073741824.0f;

inline bool isFiniteFloat(float x) { return x - x == 0.0f; }

// protocol §5. With phases of durations d1..dn (T = Σ dk) and accelerations
// ck·α (ck = +1, 0, -1), σ(t) is piecewise quadratic, and
//   σ(T) = ν0·T + α·Σk ck·(dk²/2 + dk·(dk+1 + … + dn)) = ν0·T + α·Q
// because phase k adds ck·α·dk²/2 inside itself and raises the speed by
// ck·α·dk for every phase after it. σ(T) = 1 gives ν0 = (1 − α·Q)/T.
//
// A dwell (length 0) runs σ from 0 to 1 like any segment, but every slot's
// Δ is 0, so nothing moves and L·σ' = 0. A dwell of T = 0 is an instant:
// ν0 = 0 and it ends as it starts.
//
// Fills seg.nu0 and returns false when the timing cannot be run:
//   no phase, T = 0 for a segment of length > 0, T ≥ 2^31 µs (not
//   wrap-safe), α negative or not finite,
//   or a speed below zero by more than rounding explains (durations are
//   whole µs: allow α·10 µs plus 10^-5 of the peak, in 1/s).
// Why that is enough, and what it refuses: the author rounds each phase
// boundary to the µs, so each duration is off by δk, |δk| ≤ 1 µs. Lengthening
// phase k by δ adds ν(end of k)·δ + ck·α·δ·(time after k) to σ(T), so ν0, and
// with it every boundary speed, moves by at most Σ|δk|·(peak/T + α), and the
// boundary speeds also gain α·Σ|δk|: with 3 phases, 3 µs·peak/T + 6 µs·α. A
// speed can only come near 0 in a segment that reaches its peak from rest or
// falls to rest, within T, so peak ≤ α·T and the bound is 9 µs·α < 10 µs·α;
// the 10^-5 of the peak covers float32 sums. A negative speed beyond that is
// not rounding: the author timed the segment wrongly (a clock correction that
// stretched the cruise of a segment at rest at an end made ν0 < 0; see
// core/net/segmentEncoding.ts timingEntry), and refusing it is right.
// `nuPeak` gets the largest |σ'| at any phase boundary, `nuEnd` σ'(T).
bool solveProfile(Segment& seg, float& nuPeak, float& nuEnd);

// Fixed-point coefficients of one slot moving by `delta` units along the
// segment: b0 = Δ·ν0 (Q16.16 units/µs) and cmag = Δ·α/2 (Q0.32 units/µs²).
// False if they would not fit (a speed over ~16 000 units/µs, 250 m/s).
bool slotCoefficients(float delta, float nu0, float nuPeak, float alpha, int32_t& b0, int32_t& cmag);

// σ, σ' (1/s) and σ'' (1/s²) at τ µs after the segment's start, τ clamped to
// [0, T], from the phase list. Used for status and velocity readers.
void sigmaAt(const Segment& seg, uint32_t tau, float& sigma, float& nu, float& acc);

// σ'(T): the speed at the end, 1/s.
float exitNu(const Segment& seg);

// Rounds to the nearest integer, saturating at the i32 range (and NaN to 0),
// so no input can make a float-to-int conversion undefined.
inline int32_t roundToInt(float x) {
  if (!(x == x)) return 0;
  if (x >= 2147483520.0f) return 2147483647L;
  if (x <= -2147483520.0f) return -2147483647L - 1;
  return (int32_t)(x >= 0.0f ? x + 0.5f : x - 0.5f);
}

// protocol §6, step 2: braking at `decel` (mm/s²) from speed v (mm/s) over the
// `remaining` mm of a segment. If v² ≤ 2·decel·remaining the reader stops
// inside, after v/decel s and v²/(2·decel) mm; otherwise it leaves at
// v' = √(v² − 2·decel·remaining) after (v − v')/decel s.
struct BrakePiece {
  bool stops;
  uint32_t duration;  // µs, rounded
  float distance;     // mm covered in this segment
  float exitSpeed;    // mm/s, 0 if it stops
};
BrakePiece planBrake(float v, float decel, float remaining);

// A speed is "at rest" when braking from it at `decel` would cover less than
// one position unit (2^-16 mm): v² < 2·decel·2^-16.
inline bool atRest(float v, float decel) { return v * v < 2.0f * decel * (1.0f / 65536.0f); }

}  // namespace maxl_fw

#endif
