// When to take the next sample, on the device's wrap-safe u32 µs clock.
//
// The comparison (int32_t)(now − last) < period is only meaningful while
// `last` is less than 2^31 µs (35.8 min) behind `now`. So `last` starts at
// the clock (idle(micros()) in setup()) and follows it while nothing is
// sampled: a board whose counter is already past 2^31 when sampling starts,
// or that waits an hour to be subscribed, samples at once instead of waiting
// up to 36 minutes for the difference to come back positive (the bug of
// `last = 0`).
#ifndef SAMPLE_PACER_H
#define SAMPLE_PACER_H

#include <stdint.h>

class SamplePacer {
 public:
  SamplePacer() : last_(0) {}

  // Not sampling: the next sample is due one period after `now` at the earliest.
  void idle(uint32_t now) { last_ = now; }

  // True when a sample is due at `now`, `period` µs after the last one; a
  // pacer that fell more than a period behind skips ahead to `now`.
  bool due(uint32_t now, uint32_t period) {
    if ((int32_t)(now - last_) < (int32_t)period) return false;
    last_ += period;
    if ((int32_t)(now - last_) > (int32_t)period) last_ = now;
    return true;
  }

  uint32_t last() const { return last_; }

 private:
  uint32_t last_;
};

#endif
