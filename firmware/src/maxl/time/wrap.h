// Wrap-safe comparisons of the u32 µs clock (docs/protocol.md §1):
// a is before b iff (int32_t)(a - b) < 0. Valid while the two times are less
// than 2^31 µs (35.8 min) apart, so a job may cross the 71.6-minute wrap.
#ifndef MAXL_TIME_WRAP_H
#define MAXL_TIME_WRAP_H

#include <stdint.h>

namespace maxl_fw {

inline int32_t timeDiff(uint32_t a, uint32_t b) { return (int32_t)(a - b); }
inline bool timeBefore(uint32_t a, uint32_t b) { return timeDiff(a, b) < 0; }
inline bool timeReached(uint32_t now, uint32_t t) { return timeDiff(now, t) >= 0; }

}  // namespace maxl_fw

#endif
