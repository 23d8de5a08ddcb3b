// Shared by the benchmark sketches: queue one timed trapezoid segment straight
// into a Motion (no link), the way the device's TIMING handler would.
#ifndef BENCH_TRAPEZOID_H
#define BENCH_TRAPEZOID_H

#include <math.h>

#include "maxl/motion/motion.h"
#include "maxl/motion/profile.h"
#include "maxl/wire/protocol.h"

// A segment of `length` mm from rest to rest, cruising at most at vc mm/s,
// accelerating at a mm/s², moving each of `slots` slots by delta[i] units.
inline bool benchQueueTrapezoid(maxl_fw::Motion& motion, float length, float vc, float a, const int32_t* delta,
                                uint8_t slots, uint32_t start) {
  using namespace maxl_fw;
  float vp = sqrtf(a * length);  // peak without cruise: vp² = a·L
  if (vp > vc) vp = vc;
  float tAcc = vp / a;
  float dCruise = length - vp * vp / a;
  Segment& s = motion.queue().append();
  s.length = length;
  for (uint8_t i = 0; i < slots; i++) s.p1[i] = motion.startOf(0, i) + delta[i];
  uint8_t k = 0;
  s.shape = 0;
  uint32_t acc = (uint32_t)(tAcc * 1e6f + 0.5f);
  s.shape |= (uint8_t)(phase::ACCELERATE << (2 * k));
  s.durations[k++] = acc;
  if (dCruise > 0.0f) {
    s.shape |= (uint8_t)(phase::CRUISE << (2 * k));
    s.durations[k++] = (uint32_t)(dCruise / vp * 1e6f + 0.5f);
  }
  s.shape |= (uint8_t)(phase::DECELERATE << (2 * k));
  s.durations[k++] = acc;
  s.phaseCount = k;
  s.alpha = a / length;
  float peak, end;
  if (!solveProfile(s, peak, end)) return false;
  for (uint8_t i = 0; i < slots; i++)
    if (!slotCoefficients((float)delta[i], s.nu0, peak, s.alpha, s.b0[i], s.cmag[i])) return false;
  s.start = start;
  motion.setStopDecel(a);
  motion.markTimed(1);
  return true;
}

#endif
