// An independent double-precision reading of protocol §5, for the tests to
// compare the device's fixed-point evaluation with.
#pragma once
#include <cstdint>

#include "maxl/wire/messages.h"

namespace maxltest {

struct RefState {
  double sigma;  // 0..1
  double nu;     // σ', 1/s
  double acc;    // σ'', 1/s²
};

// σ, σ', σ'' at `tau` µs after the segment's start (clamped to [0, T]).
RefState referenceSigma(const maxl_fw::msg::TimingSegment& t, double tauUs);

// The documented tolerance of a fixed-point position, in units of 2^-16 mm,
// `tau` µs into a segment of `deltaUnits` travel (see firmware/README.md).
double positionToleranceUnits(double tauUs, double deltaUnits);

}  // namespace maxltest
