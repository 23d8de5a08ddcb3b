#include "maxl/motion/profile.h"

#include <math.h>

namespace maxl_fw {

bool solveProfile(Segment& seg, float& nuPeak, float& nuEnd) {
  if (seg.phaseCount == 0) return false;
  uint32_t totalUs = 0;
  for (uint8_t k = 0; k < seg.phaseCount; k++) {
    if (seg.durations[k] >= 0x80000000UL) return false;
    totalUs += seg.durations[k];
    if (totalUs >= 0x80000000UL) return false;
  }
  float alpha = seg.alpha;
  if (!isFiniteFloat(alpha) || alpha < 0.0f) return false;
  if (totalUs == 0) {
    // An instant: only a dwell (length 0) may last no time. Nothing moves, so
    // no speed to solve; its events happen at its start.
    if (seg.length != 0.0f) return false;
    seg.nu0 = 0.0f;
    nuPeak = nuEnd = 0.0f;
    return true;
  }

  // Q = Σk ck·dk·(dk/2 + rest_k), rest_k = time after phase k (seconds).
  float q = 0.0f;
  float rest = 0.0f;
  for (int8_t k = (int8_t)seg.phaseCount - 1; k >= 0; k--) {
    float d = (float)seg.durations[k] * 1e-6f;
    int8_t c = seg.phaseSign((uint8_t)k);
    if (c) q += (float)c * d * (0.5f * d + rest);
    rest += d;
  }
  float total = (float)totalUs * 1e-6f;
  float nu0 = (1.0f - alpha * q) / total;
  if (!isFiniteFloat(nu0)) return false;

  // Speeds at the phase boundaries: the extremes of a piecewise-linear σ'.
  float nu = nu0;
  float lowest = nu0;
  float peak = fabsf(nu0);
  for (uint8_t k = 0; k < seg.phaseCount; k++) {
    nu += (float)seg.phaseSign(k) * alpha * ((float)seg.durations[k] * 1e-6f);
    if (nu < lowest) lowest = nu;
    if (fabsf(nu) > peak) peak = fabsf(nu);
  }
  float tolerance = alpha * 10e-6f + peak * 1e-5f;
  if (lowest < -tolerance) return false;
  seg.nu0 = nu0;
  nuPeak = peak;
  nuEnd = nu;
  return true;
}

bool slotCoefficients(float delta, float nu0, float nuPeak, float alpha, int32_t& b0, int32_t& cmag) {
  float peak = fabsf(delta) * nuPeak * B_SCALE;
  float b = delta * nu0 * B_SCALE;
  float c = delta * alpha * 0.5f * C_SCALE;
  if (!(peak < FIXED_LIMIT) || !(fabsf(c) < FIXED_LIMIT)) return false;
  b0 = roundToInt(b);
  cmag = roundToInt(c);
  return true;
}

void sigmaAt(const Segment& seg, uint32_t tau, float& sigma, float& nu, float& acc) {
  sigma = 0.0f;
  nu = seg.nu0;
  acc = 0.0f;
  for (uint8_t k = 0; k < seg.phaseCount; k++) {
    bool last = k + 1 == seg.phaseCount;
    uint32_t d = seg.durations[k];
    uint32_t inPhase = tau < d ? tau : d;
    float t = (float)inPhase * 1e-6f;
    acc = (float)seg.phaseSign(k) * seg.alpha;
    sigma += t * (nu + 0.5f * acc * t);
    nu += acc * t;
    if (tau < d || last) return;
    tau -= d;
  }
}

float exitNu(const Segment& seg) {
  float nu = seg.nu0;
  for (uint8_t k = 0; k < seg.phaseCount; k++)
    nu += (float)seg.phaseSign(k) * seg.alpha * ((float)seg.durations[k] * 1e-6f);
  return nu;
}

BrakePiece planBrake(float v, float decel, float remaining) {
  BrakePiece b;
  if (remaining < 0.0f) remaining = 0.0f;
  float v2 = v * v;
  float seconds;
  if (v2 <= 2.0f * decel * remaining) {
    b.stops = true;
    seconds = v / decel;
    b.distance = v2 / (2.0f * decel);
    b.exitSpeed = 0.0f;
  } else {
    b.stops = false;
    b.exitSpeed = sqrtf(v2 - 2.0f * decel * remaining);
    seconds = (v - b.exitSpeed) / decel;
    b.distance = remaining;
  }
  float us = seconds * 1e6f;
  // NaN, negative or huge (from absurd inputs) must not reach the conversion.
  b.duration = !(us > 0.0f) ? 0 : us < 1073741824.0f ? (uint32_t)(us + 0.5f) : 1073741824UL;
  return b;
}

}  // namespace maxl_fw
