// The readers of the paper (Listings 3 and 4) and the acceleration reader.
//
//   MAXL_TrackPositionLinear stepperTrack("stepper", onPositionUpdate);   // (float position mm, float delta mm)
//   MAXL_TrackVelocity velocityTrack("velocityReader", onSpeedUpdate);     // (float mm/s)
//   MAXL_TrackAcceleration accelTrack("accelReader", onAccel);             // (float mm/s²)
//   MAXL_TrackEvent laserPowerTrack("laserPower", onLaserEvent);           // (float value)
//
// Position and velocity/acceleration callbacks run from MAXL_Device::loop()
// whenever the value changed since the last call; event callbacks run once per
// change, at its time.
#ifndef MAXL_READERS_TRACKS_H
#define MAXL_READERS_TRACKS_H

#include <stdint.h>

#include "maxl/readers/reader.h"

class MAXL_TrackPositionLinear : public MAXL_Reader {
 public:
  typedef void (*Callback)(float position, float delta);
  MAXL_TrackPositionLinear(const char* name, Callback callback);

  // The last position reported, mm, and whether there is one yet (the first
  // comes with the session's first GEOMETRY p0).
  float position() const { return (float)last_ * (1.0f / 65536.0f); }
  int32_t positionUnits() const { return last_; }
  bool known() const { return known_; }

 protected:
  explicit MAXL_TrackPositionLinear(const char* name);
  // A new position in units of 2^-16 mm. `first` marks the reference of a new
  // session: where the reader is, not a move (delta 0).
  virtual void onPosition(int32_t units, bool first);

  void onTick(MAXL_Device& device);
  void onUnsubscribe();

 private:
  Callback callback_;
  int32_t last_;
  bool known_;
};

class MAXL_TrackVelocity : public MAXL_Reader {
 public:
  typedef void (*Callback)(float rate);
  MAXL_TrackVelocity(const char* name, Callback callback);
  float rate() const { return last_; }

 protected:
  void onTick(MAXL_Device& device);
  void onUnsubscribe();

 private:
  Callback callback_;
  float last_;
  bool reported_;
};

class MAXL_TrackAcceleration : public MAXL_Reader {
 public:
  typedef void (*Callback)(float acceleration);
  MAXL_TrackAcceleration(const char* name, Callback callback);
  float acceleration() const { return last_; }

 protected:
  void onTick(MAXL_Device& device);
  void onUnsubscribe();

 private:
  Callback callback_;
  float last_;
  bool reported_;
};

class MAXL_TrackEvent : public MAXL_Reader {
 public:
  typedef void (*Callback)(float value);
  MAXL_TrackEvent(const char* name, Callback callback);
  float value() const { return last_; }

 protected:
  void onEventValue(float value);
  void onUnsubscribe();

 private:
  Callback callback_;
  float last_;
};

#endif
