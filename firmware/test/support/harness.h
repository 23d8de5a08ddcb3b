// A device on the host hardware layer, driven in virtual time, plus the
// author's side of its link.
#pragma once
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "MAXL.h"
#include "maxl/hal/hal_host.h"
#include "support/author.h"

namespace maxltest {

struct Packet {
  uint8_t seq;
  uint8_t type;
  Bytes payload;
};

struct Answer {
  uint8_t seq;
  uint8_t reason;  // 0 = ACK
  uint16_t detail;
  uint8_t freeSegments;
  uint8_t freeEvents;
};

class Harness {
 public:
  explicit Harness(const char* name = "dev");

  // Virtual device clock.
  void at(uint32_t t) { maxl_fw::host::setMicros(t); }
  uint32_t now() const { return maxl_fw::host::micros(); }
  // Bytes in, then one loop().
  void send(const Bytes& frame);
  void loop() { device->loop(); }
  // Sets the clock to t and runs loop().
  void loopAt(uint32_t t) {
    at(t);
    loop();
  }

  // Everything the device sent since the last take(), decoded.
  std::vector<Packet> take();
  // The ACK/NACK answers among them (other packets dropped).
  std::vector<Answer> answers();
  // Sends a frame and returns its single answer (fails the test otherwise).
  Answer exchange(const Bytes& frame);
  // The last STATUS among what the device sent since the last take() (fails
  // the test if there is none).
  maxl_fw::msg::Status lastStatus();

  // HELLO_REQUEST then SUBSCRIBEs; expects every answer to be an ACK.
  void open(const std::vector<std::vector<uint8_t>>& subscriptions);

  std::unique_ptr<MAXL_Device> device;
  Author author;
  std::vector<Packet> pending;  // packets take() put aside for answers()
};

// A position in the wire's 16.16 fixed-point millimetres.
inline int32_t mm(double v) { return (int32_t)std::llround(v * 65536.0); }

// One TIMING segment that cruises for `us` microseconds.
inline maxl_fw::msg::TimingSegment cruise(uint32_t us) {
  maxl_fw::msg::TimingSegment t{};
  t.shape = maxl_fw::phase::CRUISE;
  t.phaseCount = 1;
  t.durations[0] = us;
  return t;
}

std::vector<Packet> decodeFrames(const uint8_t* bytes, size_t n);
Answer answerOf(const Packet& p);

}  // namespace maxltest
