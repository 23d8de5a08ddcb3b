// One queued segment: geometry (protocol §4 GEOMETRY) and, once it has it,
// timing (TIMING) with the fixed-point coefficients derived from it.
//
// The segment's own id is not stored: ids in the queue are consecutive, so
// the queue knows them from the head's. Its p0 is not stored either: it is
// the previous segment's p1 (or the queue's base position for the head).
#ifndef MAXL_MOTION_SEGMENT_H
#define MAXL_MOTION_SEGMENT_H

#include <stdint.h>

#include "maxl/config.h"

namespace maxl_fw {

struct Segment {
  // geometry
  float length;                       // L, mm along the path
  int32_t p1[MAXL_POSITION_SLOTS];    // each slot's position at the end, units of 2^-16 mm

  // timing (valid for the queue's timed prefix)
  uint32_t start;                     // device µs
  uint32_t durations[3];              // µs per phase
  uint8_t shape;                      // phase kinds, two bits each (protocol §4 TIMING)
  uint8_t phaseCount;
  float alpha;                        // normalised path acceleration a/L, 1/s²
  float nu0;                          // σ'(0), 1/s: (1 - α·Q)/T, protocol §5
  int32_t b0[MAXL_POSITION_SLOTS];    // Δ·ν0 per slot, units/µs in Q16.16 (fixed_point.h)
  int32_t cmag[MAXL_POSITION_SLOTS];  // Δ·α/2 per slot, units/µs² in Q0.32

  uint32_t duration() const { return durations[0] + durations[1] + durations[2]; }
  uint32_t end() const { return start + duration(); }
  // +1 accelerate, 0 cruise, -1 decelerate
  int8_t phaseSign(uint8_t k) const {
    uint8_t kind = (uint8_t)((k == 0 ? shape : k == 1 ? shape >> 2 : shape >> 4) & 3);  // k < 3
    return kind == 1 ? 1 : kind == 3 ? -1 : 0;
  }
};

}  // namespace maxl_fw

#endif
