// The author's side of the link, for tests: builds frames with the library's
// own encoders (the shared vectors check those against the TS codec), and
// simple timing profiles.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "maxl/wire/bytes.h"
#include "maxl/wire/messages.h"
#include "maxl/wire/protocol.h"

namespace maxltest {

using Bytes = std::vector<uint8_t>;

Bytes frame(uint8_t seq, uint8_t type, const std::function<void(maxl_fw::ByteWriter&)>& body);

struct GeometrySegment {
  float length;
  std::vector<int32_t> p1;
};

// Trapezoid timing of a segment of `length` mm entered at ve, left at vx,
// cruising at most at vc (mm/s), accelerating at a (mm/s²): durations rounded
// to whole µs, alpha = a/L (protocol §4 TIMING).
maxl_fw::msg::TimingSegment trapezoid(double length, double ve, double vc, double vx, double a);
// Exit speed of a trapezoid as the device computes it, mm/s (from σ(T) = 1).
double exitSpeed(const maxl_fw::msg::TimingSegment& t, double length);
uint32_t durationOf(const maxl_fw::msg::TimingSegment& t);

class Author {
 public:
  uint8_t seq = 0;

  Bytes helloRequest(uint8_t protocol = maxl_fw::PROTOCOL_VERSION);
  Bytes ping(uint16_t pingId, uint16_t replyAfter = 0);
  Bytes clock(uint32_t deviceRef, uint32_t authorRef, int32_t ratePpb);
  Bytes subscribe(uint8_t reader, uint8_t kind, uint8_t slot);
  Bytes geometry(uint16_t firstId, const std::vector<int32_t>* p0, const std::vector<GeometrySegment>& segments,
                 uint8_t positionSlots);
  Bytes timing(uint16_t firstId, float stopDecel, const uint32_t* start,
               const std::vector<maxl_fw::msg::TimingSegment>& segments);
  Bytes events(uint16_t segmentId, uint8_t slot, uint16_t firstIndex,
               const std::vector<maxl_fw::msg::EventEntry>& entries);
  Bytes replaceTail(uint16_t fromId);
  Bytes halt(uint8_t mode, uint32_t at);
  Bytes statusRequest();
  Bytes raw(uint8_t type, const Bytes& payload);
};

}  // namespace maxltest
