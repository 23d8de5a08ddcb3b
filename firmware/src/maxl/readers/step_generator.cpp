#include "maxl/readers/step_generator.h"

namespace {
// ceil(q / 2^16) for a Q16 value, clamped to the i32 range.
int32_t ceilUnits(int64_t q) {
  int64_t c = (q + 0xFFFF) >> 16;  // arithmetic shift: floor, so this is ceil
  if (c > 2147483647LL) return 2147483647L;
  if (c < -2147483647LL - 1) return -2147483647L - 1;
  return (int32_t)c;
}
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
  // s·2^16 = 2^32 / stepsPerUnit; at least 1 so that the loops below end.
  float q = stepsPerUnit > 0.0f ? 4294967296.0f / stepsPerUnit : 4294967296.0f;
  if (q < 1.0f) q = 1.0f;
  if (q > 9.0e15f) q = 9.0e15f;
  stepQ_ = (int64_t)q;
  reference(0);
}

void MAXL_StepGenerator::begin() {
  if (begun_) return;
  begun_ = true;
  maxl_fw::hal::makeOutput(stepPin_, stepPinNumber_);
  maxl_fw::hal::makeOutput(dirPin_, dirPinNumber_);
  maxl_fw::hal::writePin(stepPin_, false);
}

void MAXL_StepGenerator::refreshCeilings() {
  upCeil_ = ceilUnits(upQ_);
  downCeil_ = ceilUnits(upQ_ - stepQ_);
}

void MAXL_StepGenerator::reference(int32_t units) {
  // n = floor(p/s + 1/2) = floor((2·p·2^16 + s_q) / (2·s_q))
  int64_t n = floorDiv(2 * ((int64_t)units * 65536) + stepQ_, 2 * stepQ_);
  steps_ = (int32_t)n;
  upQ_ = n * stepQ_ + stepQ_ / 2;
  refreshCeilings();
}

void MAXL_StepGenerator::moveTo(int32_t units) {
  while (units >= upCeil_) {
    step(1);
    upQ_ += stepQ_;
    refreshCeilings();
  }
  while (units < downCeil_) {
    step(-1);
    upQ_ -= stepQ_;
    refreshCeilings();
  }
}

void MAXL_StepGenerator::step(int8_t direction) {
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
