// The author's clock as the device can read it (protocol §4 CLOCK):
//   author_us = authorRef + (device_us − deviceRef)·(1 + ratePpb·10^-9), mod 2^32.
// The difference is taken wrap-safe (signed 32-bit), so it is valid within
// ±35 minutes of deviceRef; the author refreshes CLOCK well within that.
#ifndef MAXL_TIME_CLOCK_MODEL_H
#define MAXL_TIME_CLOCK_MODEL_H

#include <stdint.h>

namespace maxl_fw {

class ClockModel {
 public:
  ClockModel() : known_(false), deviceRef_(0), authorRef_(0), ratePpb_(0) {}
  void set(uint32_t deviceRef, uint32_t authorRef, int32_t ratePpb) {
    deviceRef_ = deviceRef;
    authorRef_ = authorRef;
    ratePpb_ = ratePpb;
    known_ = true;
  }
  bool known() const { return known_; }
  // Author µs at device time `device`; the device time itself until a CLOCK arrived.
  uint32_t authorTime(uint32_t device) const {
    if (!known_) return device;
    int32_t d = (int32_t)(device - deviceRef_);
    // d·ratePpb/10^9 rounded to nearest; |d·ratePpb| < 2^62.
    int64_t scaled = (int64_t)d * ratePpb_;
    int64_t correction = (scaled >= 0 ? scaled + 500000000LL : scaled - 500000000LL) / 1000000000LL;
    return authorRef_ + (uint32_t)d + (uint32_t)(int32_t)correction;
  }

 private:
  bool known_;
  uint32_t deviceRef_;
  uint32_t authorRef_;
  int32_t ratePpb_;
};

}  // namespace maxl_fw

#endif
