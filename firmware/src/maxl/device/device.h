// The device: one per board. It owns the link, the session, the segment and
// event queues and the readers' bindings, and runs them from loop().
//
//   MAXL_Device maxl("motorOne");
//   void setup() { maxl.begin(Serial); }
//   void loop()  { maxl.loop(); }
#ifndef MAXL_DEVICE_DEVICE_H
#define MAXL_DEVICE_DEVICE_H

#include <stdint.h>

#include "maxl/config.h"
#include "maxl/events/event_queue.h"
#include "maxl/hal/hal.h"
#include "maxl/motion/motion.h"
#include "maxl/session/session.h"
#include "maxl/time/clock_model.h"
#include "maxl/wire/frame_receiver.h"
#include "maxl/wire/frame_writer.h"

class MAXL_Reader;

class MAXL_Device {
 public:
  explicit MAXL_Device(const char* name);

  // Starts the link on `port` (Serial, ...) at `baud` and the runtime.
  template <class Port>
  void begin(Port& port, uint32_t baud = MAXL_DEFAULT_BAUD) {
    port.begin(baud);
    maxl_fw::hal::attach(port);
    begin();
  }
  // Starts the runtime on a link that is already up (host tests, wasm).
  void begin();
  // Reads the link, runs the trajectory, calls the readers. Call it as often
  // as possible: every position reader is evaluated once per call.
  void loop();

  const char* name() const { return name_; }

  // ---- clocks
  // Device time of the current loop() (µs: the u32 micros() counter, less
  // the clock jumps mended since power-up; see readClock()).
  uint32_t now() const { return now_; }
  // The device clock at this instant (micros() less the jumps mended).
  uint32_t clockNow() const { return maxl_fw::hal::micros() - clockSkew_; }
  // The author's ("machine") time now and at a device time, from CLOCK; until
  // a CLOCK arrives, the device time itself (see clockKnown()).
  uint32_t machineTime() const { return clock_.authorTime(clockNow()); }
  uint32_t machineTimeAt(uint32_t deviceTime) const { return clock_.authorTime(deviceTime); }
  bool clockKnown() const { return clock_.known(); }

  // ---- state
  uint8_t state() const { return motion_.statusState(); }  // STATUS.state
  uint8_t statusFlags() const { return flags_; }
  // Nothing is due before new input arrives: no timing, no braking, no
  // pending event, no subscribed sensor. The simulator calls loop() rarely then.
  bool idle() const;
  // µs until loop() next has something to do, without new input: 0 when it has
  // work now, 0xFFFFFFFF when nothing is due at all. A board ignores this; the
  // simulator uses it to sleep a device until a delayed PONG is due.
  uint32_t wakeAfter() const;

  // ---- for readers
  bool positionKnown(uint8_t slot) const { return slot < motion_.knownSlots(); }
  int32_t positionUnits(uint8_t slot) const { return motion_.position(slot); }
  float velocity();      // path speed at now(), mm/s
  float acceleration();  // path acceleration at now(), mm/s²
  // False (nothing sent; try again later) while a frame is being received.
  bool sendSamples(uint8_t reader, uint16_t sampleSeq, uint8_t count, uint32_t t0, const uint8_t* bytes,
                   uint8_t length);

  // Bytes of a STATUS or SAMPLES frame written per loop() (0: all at once);
  // the default is MAXL_TX_BYTES_PER_LOOP.
  void setTransmitPacing(uint8_t bytesPerLoop) { txPacing_ = bytesPerLoop; }

  static MAXL_Device* instance() { return instance_; }
  const maxl_fw::Motion& motion() const { return motion_; }

 private:
  struct Answer {
    uint8_t reason;  // 0: ack
    uint16_t detail;
  };
  static Answer ack() {
    Answer a = {0, 0};
    return a;
  }
  static Answer nack(uint8_t reason, uint16_t detail) {
    Answer a = {reason, detail};
    return a;
  }
  struct EventTrack {  // EVENTS continuation state of one event slot
    bool active;
    uint16_t segmentId;
    uint16_t next;        // entries received for that segment
    uint32_t lastOffset;  // offset of the last one
  };

  // link (device_link.cpp)
  void pollLink();
  void onPacket();
  void onFrameError(maxl_fw::CodecError error);
  void startSession(uint8_t seq, uint8_t protocol);
  void sendAnswer(uint8_t seq, uint8_t reason, uint16_t detail);
  void sendHello();
  void sendReader(uint8_t index);
  void sendStatus();
  bool idleBesidesPong() const;
  void sendPong(bool paced);
  maxl_fw::ByteWriter& beginFrame(uint8_t type);
  void sendFrame();
  void sendFramePaced();
  void pumpTransmit();
  void flushTransmit();

  // handlers (device_handlers.cpp)
  Answer handle(uint8_t type, const uint8_t* payload, uint8_t length);
  Answer onPing(const uint8_t* p, uint8_t n);
  Answer onClock(const uint8_t* p, uint8_t n);
  Answer onSubscribe(const uint8_t* p, uint8_t n);
  Answer onGeometry(const uint8_t* p, uint8_t n);
  Answer onTiming(const uint8_t* p, uint8_t n);
  Answer onEvents(const uint8_t* p, uint8_t n);
  Answer onReplaceTail(const uint8_t* p, uint8_t n);
  Answer onHalt(const uint8_t* p, uint8_t n);
  void forgetEventTracksFrom(uint16_t segmentId);

  // runtime (device.cpp)
  void readClock();
  void resetSession();
  void fireEvents();
  void reportStatus();

  static MAXL_Device* instance_;

  const char* name_;
  // One buffer for both directions: handlers read their packet completely
  // before they write a reply (see frame_receiver.h). With MAXL_TX_BUFFER,
  // frames are written in a buffer of their own.
  uint8_t frameBuffer_[maxl_fw::FRAME_BUFFER_SIZE];
#if MAXL_TX_BUFFER
  uint8_t txBuffer_[maxl_fw::FRAME_BUFFER_SIZE];
#endif
  // Whether a frame being received holds the buffer reports are written in.
  bool receivingIntoTxBuffer() const { return !MAXL_TX_BUFFER && rx_.inFrame(); }
  maxl_fw::FrameReceiver rx_;
  maxl_fw::FrameWriter tx_;
  maxl_fw::Session session_;
  maxl_fw::Motion motion_;
  maxl_fw::EventQueue events_;
  maxl_fw::ClockModel clock_;
  EventTrack eventTracks_[MAXL_EVENT_SLOTS];
  uint32_t now_;
  uint32_t clockSkew_;  // micros() − device time: the sum of the jumps mended
  uint32_t lastStatusAt_;
  float velocity_;
  float acceleration_;
  uint8_t txSeq_;
  uint8_t flags_;
  uint8_t lastState_;
  // flags as bits: every byte counts on a 2 KB board
  bool begun_ : 1;
  bool velocityValid_ : 1;
  bool accelerationValid_ : 1;
  bool statusPending_ : 1;  // a STATUS is due but a frame was arriving
  bool pongPending_ : 1;    // a PONG waits for its reply time (PING replyAfter)
  bool clockWatched_ : 1;   // the last loop() ran or awaited timing: the next read is checked
  uint16_t pongId_;
  uint32_t pongReceivedAt_;
  uint32_t pongDueAt_;
  uint8_t txPacing_;
  uint8_t txSent_;      // bytes of the paced frame in frameBuffer_ already written
  uint8_t txLength_;    // its length; 0 when nothing is pending
};

#endif
