#include "maxl/readers/step_generator.h"

namespace {
// floor(a / b) for b > 0 (C++ division truncates towards zero).
int64_t floorDiv(int64_t a, int64_t b) {
  int64_t q = a / b;
  if ((a % b != 0) && (a < 0)) q--;
  return q;
}
}  // namespace

MAXL_StepGenerator::MAXL_StepGenerator(uint8_t stepPin, uint8_t dirPin, float stepsPerUnit, bool invertDirection)
    : stepPinNumber_(stepPin),
      dirPinNumber_(dirPin),
      invert_(invertDirection),
      begun_(false),
      direction_(0),
      stepsPerUnit_(stepsPerUnit),
      steps_(0) {
  stepPin_.valid = false;
  dirPin_.valid = false;
  // s·2^16 = 2^32 / stepsPerUnit, at least 1 (so that stepping ends) and
  // below 2^47 (s below 2^31 units, 32 m per step).
  float q = stepsPerUnit > 0.0f ? 4294967296.0f / stepsPerUnit : 4294967296.0f;
  if (!(q >= 1.0f)) q = 1.0f;
  if (q > 1.4e14f) q = 1.4e14f;
  int64_t stepQ = (int64_t)q;
  sWhole_ = (int32_t)(stepQ >> 16);
  sFrac_ = (uint16_t)(stepQ & 0xFFFF);
  reference(0);
}

void MAXL_StepGenerator::begin() {
  if (begun_) return;
  begun_ = true;
  maxl_fw::hal::makeOutput(stepPin_, stepPinNumber_);
  maxl_fw::hal::makeOutput(dirPin_, dirPinNumber_);
  maxl_fw::hal::writePin(stepPin_, false);
}


// Ceilings of the thresholds from the exact upper one, 32-bit only (this runs
// on every step). With up = U + f/2^16 and s = S + g/2^16:
//   ceil(up)     = U + (f != 0)
//   down = up − s = (U − S) + (f − g)/2^16, so
//   ceil(down)   = U − S + 1 if f > g; U − S if f == g; and if f < g,
//                  (U − S − 1) + ceil((f − g + 2^16)/2^16) = U − S.
inline __attribute__((always_inline)) void MAXL_StepGenerator::refreshCeilings() {
  upCeil_ = (int32_t)((uint32_t)upWhole_ + (upFrac_ != 0));
  downCeil_ = (int32_t)((uint32_t)upWhole_ - (uint32_t)sWhole_ + (upFrac_ > sFrac_));
}

void MAXL_StepGenerator::reference(int32_t units) {
  // n = floor(p/s + 1/2) = floor((2·p·2^16 + s_q) / (2·s_q)), s_q = s·2^16
  int64_t stepQ = (int64_t)sWhole_ * 65536 + sFrac_;
  int64_t n = floorDiv(2 * ((int64_t)units * 65536) + stepQ, 2 * stepQ);
  steps_ = (int32_t)n;
  int64_t upQ = n * stepQ + stepQ / 2;  // (n + 1/2)·s in Q16
  upWhole_ = (int32_t)floorDiv(upQ, 65536);
  upFrac_ = (uint16_t)(upQ - (int64_t)upWhole_ * 65536);
  refreshCeilings();
}

inline __attribute__((always_inline)) void MAXL_StepGenerator::step(int8_t direction) {
  if (!begun_) begin();
  if (direction != direction_) {
    maxl_fw::hal::writePin(dirPin_, (direction > 0) != invert_);
    maxl_fw::hal::directionSetupWait();
    direction_ = direction;
  }
  maxl_fw::hal::writePin(stepPin_, true);
  maxl_fw::hal::stepPulseWait();
  maxl_fw::hal::writePin(stepPin_, false);
  steps_ += direction;
}

bool MAXL_StepGenerator::moveTo(int32_t units) {
  uint8_t budget = MAXL_MAX_STEPS_PER_EVALUATION;
  while (units >= upCeil_) {
    if (!budget--) return false;
    step(1);
    uint16_t frac = (uint16_t)(upFrac_ + sFrac_);
    upWhole_ = (int32_t)((uint32_t)upWhole_ + (uint32_t)sWhole_ + (frac < upFrac_ ? 1u : 0u));
    upFrac_ = frac;
    refreshCeilings();
  }
  while (units < downCeil_) {
    if (!budget--) return false;
    step(-1);
    uint16_t frac = (uint16_t)(upFrac_ - sFrac_);
    upWhole_ = (int32_t)((uint32_t)upWhole_ - (uint32_t)sWhole_ - (upFrac_ < sFrac_ ? 1u : 0u));
    upFrac_ = frac;
    refreshCeilings();
  }
  return true;
}

