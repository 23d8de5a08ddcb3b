#include "maxl/readers/tracks.h"

#include "maxl/device/device.h"
#include "maxl/wire/protocol.h"

// ---------------------------------------------------------------- position

MAXL_TrackPositionLinear::MAXL_TrackPositionLinear(const char* name, Callback callback)
    : MAXL_Reader(name, maxl_fw::kind::POSITION, 0), callback_(callback), last_(0), known_(false) {}

MAXL_TrackPositionLinear::MAXL_TrackPositionLinear(const char* name)
    : MAXL_Reader(name, maxl_fw::kind::POSITION, 0), callback_(0), last_(0), known_(false) {}

void MAXL_TrackPositionLinear::onTick(MAXL_Device& device) {
  if (!device.positionKnown(slot())) return;
  int32_t p = device.positionUnits(slot());
  if (known_ && p == last_) return;
  bool first = !known_;
  onPosition(p, first);
  known_ = true;
  last_ = p;
}

// The delta is taken in integer units, then converted: summing the deltas
// gives exactly the position, with no float drift.
void MAXL_TrackPositionLinear::onPosition(int32_t units, bool first) {
  if (!callback_) return;
  int32_t delta = first ? 0 : (int32_t)((uint32_t)units - (uint32_t)last_);
  callback_((float)units * (1.0f / 65536.0f), (float)delta * (1.0f / 65536.0f));
}

void MAXL_TrackPositionLinear::onUnsubscribe() { known_ = false; }

// ---------------------------------------------------------------- velocity

MAXL_TrackVelocity::MAXL_TrackVelocity(const char* name, Callback callback)
    : MAXL_Reader(name, maxl_fw::kind::VELOCITY, 0), callback_(callback), last_(0.0f), reported_(false) {}

void MAXL_TrackVelocity::onTick(MAXL_Device& device) {
  float v = device.velocity();
  if (reported_ && v == last_) return;
  last_ = v;
  reported_ = true;
  if (callback_) callback_(v);
}

void MAXL_TrackVelocity::onUnsubscribe() { reported_ = false; }

// ---------------------------------------------------------------- acceleration

MAXL_TrackAcceleration::MAXL_TrackAcceleration(const char* name, Callback callback)
    : MAXL_Reader(name, maxl_fw::kind::ACCELERATION, 0), callback_(callback), last_(0.0f), reported_(false) {}

void MAXL_TrackAcceleration::onTick(MAXL_Device& device) {
  float a = device.acceleration();
  if (reported_ && a == last_) return;
  last_ = a;
  reported_ = true;
  if (callback_) callback_(a);
}

void MAXL_TrackAcceleration::onUnsubscribe() { reported_ = false; }

// ---------------------------------------------------------------- event

MAXL_TrackEvent::MAXL_TrackEvent(const char* name, Callback callback)
    : MAXL_Reader(name, maxl_fw::kind::EVENT, 0), callback_(callback), last_(0.0f) {}

void MAXL_TrackEvent::onEventValue(float value) {
  last_ = value;
  if (callback_) callback_(value);
}

void MAXL_TrackEvent::onUnsubscribe() {}
