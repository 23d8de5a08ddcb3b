// Shared by the benchmark sketches: a path of short pieces for the cycle bench,
// queued straight into a Motion (no link) the way the TIMING handler would, a
// few segments ahead of the clock as a stream keeps them.
//
// The path is an Archimedean spiral r = R0 + K·θ in two slots (x, y), cut into
// chords of PIECE_MM. Its speed profile is what a planner gives a path of short
// pieces: from rest up to VMAX at ACCEL, down to VSLOW and up again half-way (a
// sharp corner), and down to rest at the end. Every piece has its own entry and
// exit speeds, so pieces hold one, two or three phases, some of a few µs, and a
// segment ends every PIECE_MM / v (3.3 ms at VMAX): the case issue 14 item 4
// names, the work at a segment's end, every few ms.
#ifndef BENCH_SPIRAL_H
#define BENCH_SPIRAL_H

#include <math.h>

#include "maxl/motion/motion.h"
#include "maxl/motion/profile.h"
#include "maxl/wire/protocol.h"

namespace bench_spiral {

const float PIECE_MM = 0.5f;
const uint16_t PIECES = 600;  // 300 mm of path
const float VMAX = 150.0f;    // mm/s
const float VSLOW = 20.0f;    // mm/s at the corner half-way
const float ACCEL = 3000.0f;  // mm/s²
const float R0 = 2.0f;        // mm
const float K = 1.5f / (2.0f * (float)M_PI);  // 1.5 mm between turns

// Largest speed at the junction after piece i (i = PIECES - 1: the end), from
// the three limits: accelerating from rest at the start (v² = 2·a·s), braking
// to VSLOW at the corner and to rest at the end (the same, backwards), VMAX.
// Pieces are all PIECE_MM long as far as the speed plan is concerned, so every
// piece can go from its entry to its exit speed at ACCEL (both limits hold on
// both sides of it).
inline float junctionSpeed(uint16_t i) {
  if (i + 1 >= PIECES) return 0.0f;
  const uint16_t corner = PIECES / 2;
  float fromStart = sqrtf(2.0f * ACCEL * PIECE_MM * (float)(i + 1));
  float toEnd = sqrtf(2.0f * ACCEL * PIECE_MM * (float)(PIECES - 1 - i));
  uint16_t fromCorner = i + 1 >= corner ? (uint16_t)(i + 1 - corner) : (uint16_t)(corner - i - 1);
  float corner2 = sqrtf(VSLOW * VSLOW + 2.0f * ACCEL * PIECE_MM * (float)fromCorner);
  float v = VMAX;
  if (fromStart < v) v = fromStart;
  if (toEnd < v) v = toEnd;
  if (corner2 < v) v = corner2;
  return v;
}

class Spiral {
 public:
  // Starts at θ = 0 on `motion` (slots 0 and 1 at the spiral's start), the
  // first piece at device time `start`.
  void begin(maxl_fw::Motion& motion, uint32_t start) {
    theta_ = 0.0f;
    next_ = 0;
    start_ = start;
    vIn_ = 0.0f;
    motion.reset();
    motion.setActiveSlots(2);
    point(x_, y_);
    int32_t p0[2] = {x_, y_};
    motion.setBase(p0, 2);
    motion.setStopDecel(ACCEL);
  }
  bool done() const { return next_ >= PIECES; }
  // Queues pieces while the queue has room (the TIMING handler's work).
  void refill(maxl_fw::Motion& motion) {
    while (!done() && motion.queue().free() > 0) queueNext(motion);
  }

 private:
  void point(int32_t& x, int32_t& y) const {
    float r = R0 + K * theta_;
    x = (int32_t)lroundf(r * cosf(theta_) * maxl_fw::UNITS_PER_MM);
    y = (int32_t)lroundf(r * sinf(theta_) * maxl_fw::UNITS_PER_MM);
  }

  // One piece: the chord to the point PIECE_MM further along the spiral
  // (dθ = ds / √(r² + K²)), from speed vIn_ to its junction speed, as a
  // trapezoid capped at VMAX: peak vp² = (2·a·L + vIn² + vOut²)/2.
  void queueNext(maxl_fw::Motion& motion) {
    using namespace maxl_fw;
    float r = R0 + K * theta_;
    theta_ += PIECE_MM / sqrtf(r * r + K * K);
    int32_t x, y;
    point(x, y);
    int32_t delta[2] = {x - x_, y - y_};
    float length = sqrtf((float)delta[0] * (float)delta[0] + (float)delta[1] * (float)delta[1]) / UNITS_PER_MM;
    float vOut = junctionSpeed(next_);
    float vp = sqrtf((2.0f * ACCEL * length + vIn_ * vIn_ + vOut * vOut) * 0.5f);
    if (vp > VMAX) vp = VMAX;
    if (vp < vIn_) vp = vIn_;
    if (vp < vOut) vp = vOut;
    float dAcc = (vp * vp - vIn_ * vIn_) / (2.0f * ACCEL);
    float dDec = (vp * vp - vOut * vOut) / (2.0f * ACCEL);
    float dCruise = length - dAcc - dDec;
    Segment& s = motion.queue().append();
    uint8_t index = (uint8_t)(motion.queue().count() - 1);
    s.length = length;
    s.p1[0] = x;
    s.p1[1] = y;
    s.shape = 0;
    uint8_t k = 0;
    uint32_t us = (uint32_t)lroundf((vp - vIn_) / ACCEL * 1e6f);
    if (us > 0) {
      s.shape |= (uint8_t)(phase::ACCELERATE << (2 * k));
      s.durations[k++] = us;
    }
    us = dCruise > 0.0f ? (uint32_t)lroundf(dCruise / vp * 1e6f) : 0;
    if (us > 0) {
      s.shape |= (uint8_t)(phase::CRUISE << (2 * k));
      s.durations[k++] = us;
    }
    us = (uint32_t)lroundf((vp - vOut) / ACCEL * 1e6f);
    if (us > 0 || k == 0) {
      s.shape |= (uint8_t)(phase::DECELERATE << (2 * k));
      s.durations[k++] = us;
    }
    s.phaseCount = k;
    while (k < 3) s.durations[k++] = 0;
    s.alpha = ACCEL / length;
    float peak, end;
    bool ok = solveProfile(s, peak, end);
    for (uint8_t i = 0; i < 2 && ok; i++) {
      float d = (float)((int64_t)s.p1[i] - (int64_t)motion.startOf(index, i));
      ok = slotCoefficients(d, s.nu0, peak, s.alpha, s.b0[i], s.cmag[i]);
    }
    if (!ok) {  // never with the constants above; stop the bench loudly if so
      Serial.print("FAIL spiral piece ");
      Serial.println(next_);
      next_ = PIECES;
      return;
    }
    s.start = start_;
    start_ += s.duration();
    motion.markTimed(motion.queue().count());
    x_ = x;
    y_ = y;
    vIn_ = vOut;
    next_++;
  }

  float theta_;
  float vIn_;
  int32_t x_, y_;
  uint32_t start_;
  uint16_t next_;
};

}  // namespace bench_spiral

#endif
