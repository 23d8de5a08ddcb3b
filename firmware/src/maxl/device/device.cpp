// MAXL_Device: construction, the loop, readers, events and status.
// The link and session are in device_link.cpp, message handling in
// device_handlers.cpp.
#include "maxl/device/device.h"

#include "maxl/readers/reader.h"
#include "maxl/time/wrap.h"
#include "maxl/wire/protocol.h"

using namespace maxl_fw;

MAXL_Device* MAXL_Device::instance_ = 0;

MAXL_Device::MAXL_Device(const char* name)
    : name_(name),
      frameBuffer_(),
#if MAXL_TX_BUFFER
      txBuffer_(),
      rx_(frameBuffer_),
      tx_(txBuffer_),
#else
      rx_(frameBuffer_),
      tx_(frameBuffer_),
#endif
      now_(0),
      clockSkew_(0),
      lastStatusAt_(0),
      velocity_(0.0f),
      acceleration_(0.0f),
      txSeq_(0),
      flags_(0),
      lastState_(state::IDLE),
      begun_(false),
      velocityValid_(false),
      accelerationValid_(false),
      statusPending_(false),
      pongPending_(false),
      clockWatched_(false),
      pongId_(0),
      pongReceivedAt_(0),
      pongDueAt_(0),
      txPacing_(MAXL_TX_BYTES_PER_LOOP),
      txSent_(0),
      txLength_(0) {
  instance_ = this;
  for (uint8_t i = 0; i < MAXL_EVENT_SLOTS; i++) eventTracks_[i].active = false;
}

void MAXL_Device::begin() {
  instance_ = this;
  begun_ = true;
  session_.end();
  resetSession();
  for (MAXL_Reader* r = MAXL_Reader::first(); r; r = r->next()) r->onBegin();
  now_ = clockNow();
  lastStatusAt_ = now_;
}

// now_ = the device clock, checked for a jump (config.h MAXL_CLOCK_JUMP_US).
// While timing is held, the step d from the last read must lie in
// [0, MAXL_CLOCK_JUMP_US]. Outside it the counter jumped by d − (the loop's
// real length); that length is unknown but at most the bound, so the jump is
// mended as if the loop had taken no time (clockSkew_ += d: the clock goes on
// from the last read, off by at most one loop). Nothing is evaluated at the
// jumped time, so the readers never move ahead or back along the path. The
// device then takes no more TIMING (nack CLOCK_JUMP) and reports the flag at
// once: it runs out of what it holds and brakes to rest on the path, as every
// other board does once the author stops streaming. Nothing resets the skew
// but power: a new session simply runs on the mended clock.
void MAXL_Device::readClock() {
  uint32_t t = clockNow();
#if MAXL_CLOCK_JUMP_US
  int32_t d = timeDiff(t, now_);
  if (clockWatched_ && (d < 0 || d > (int32_t)MAXL_CLOCK_JUMP_US)) {
    clockSkew_ += (uint32_t)d;
    t = now_;
    flags_ |= status_flag::CLOCK_JUMP;
    statusPending_ = true;
  }
#endif
  now_ = t;
}

// A new session (HELLO_REQUEST), or power-up: nothing queued, nothing
// subscribed, flags cleared. The clock model is kept: it is about the clocks,
// not the session.
void MAXL_Device::resetSession() {
  motion_.reset();
  events_.clear();
  for (uint8_t i = 0; i < MAXL_EVENT_SLOTS; i++) eventTracks_[i].active = false;
  for (MAXL_Reader* r = MAXL_Reader::first(); r; r = r->next()) r->unbind();
  flags_ = 0;
  lastState_ = motion_.statusState();
  statusPending_ = false;
  pongPending_ = false;
}

void MAXL_Device::loop() {
  if (!begun_) return;
  pumpTransmit();
  pollLink();
  readClock();
  motion_.tick(now_);
  // Timing queued (waiting or running) or braking: the next read is checked.
  clockWatched_ = motion_.statusState() == state::RUNNING || motion_.statusState() == state::BRAKING;
  velocityValid_ = accelerationValid_ = false;
  for (MAXL_Reader* r = MAXL_Reader::first(); r; r = r->next())
    if (r->subscribed()) r->onTick(*this);
  fireEvents();
  if (motion_.takeStarved()) flags_ |= status_flag::STARVED;
  if (pongPending_ && timeDiff(now_, pongDueAt_) >= 0 && !receivingIntoTxBuffer() && txLength_ == 0) sendPong(true);
  reportStatus();
}

float MAXL_Device::velocity() {
  if (!velocityValid_) {
    velocity_ = motion_.velocity(now_);
    velocityValid_ = true;
  }
  return velocity_;
}

float MAXL_Device::acceleration() {
  if (!accelerationValid_) {
    acceleration_ = motion_.acceleration(now_);
    accelerationValid_ = true;
  }
  return acceleration_;
}

void MAXL_Device::fireEvents() {
  if (!events_.due(now_)) return;
  EventEntry e;
  while (events_.popDue(now_, e)) {
    for (MAXL_Reader* r = MAXL_Reader::first(); r; r = r->next())
      if (r->subscribed() && r->kind() == kind::EVENT && r->slot() == e.slot) r->onEventValue(e.value);
  }
}

// STATUS on every state change, and every MAXL_STATUS_PERIOD_US while not
// idle. The transmit buffer is also the receive buffer (device.h): while a
// frame is arriving the STATUS waits, and goes out once it is complete
// (pollLink() stops after a frame while one waits, so there is a moment between frames).
void MAXL_Device::reportStatus() {
  if (!session_.active()) return;
  uint8_t s = motion_.statusState();
  if (s != lastState_) {
    lastState_ = s;
    statusPending_ = true;
  } else if (s != state::IDLE && timeDiff(now_, lastStatusAt_) >= (int32_t)MAXL_STATUS_PERIOD_US) {
    statusPending_ = true;
  }
  if (statusPending_ && !receivingIntoTxBuffer() && txLength_ == 0) sendStatus();
}

uint32_t MAXL_Device::wakeAfter() const {
  if (!idleBesidesPong()) return 0;
  if (!pongPending_) return 0xFFFFFFFFul;
  int32_t wait = timeDiff(pongDueAt_, now_);
  return wait > 0 ? (uint32_t)wait : 0;
}

bool MAXL_Device::idle() const { return !pongPending_ && idleBesidesPong(); }

bool MAXL_Device::idleBesidesPong() const {
  if (txLength_ || statusPending_) return false;
  if (motion_.statusState() != state::IDLE || motion_.queue().timed() > 0 || events_.count() > 0) return false;
  for (const MAXL_Reader* r = MAXL_Reader::first(); r; r = r->next())
    if (r->subscribed() && r->kind() == kind::SENSOR) return false;
  return true;
}
