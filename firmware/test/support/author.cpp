#include "support/author.h"

#include <cmath>
#include <stdexcept>

#include "maxl/wire/frame_writer.h"

namespace maxltest {

Bytes frame(uint8_t seq, uint8_t type, const std::function<void(maxl_fw::ByteWriter&)>& body) {
  maxl_fw::OwnedFrameWriter w;
  body(w.begin(seq, type));
  if (!w.finish()) throw std::runtime_error("payload too long");
  return Bytes(w.frame(), w.frame() + w.frameLength());
}

maxl_fw::msg::TimingSegment trapezoid(double L, double ve, double vc, double vx, double a) {
  double vp2 = std::min(vc * vc, (2 * a * L + ve * ve + vx * vx) / 2);
  vp2 = std::max({vp2, ve * ve, vx * vx});
  double vp = std::sqrt(vp2);
  double dAcc = (vp2 - ve * ve) / (2 * a), dDec = (vp2 - vx * vx) / (2 * a);
  double dCruise = std::max(0.0, L - dAcc - dDec);
  maxl_fw::msg::TimingSegment t{};
  uint8_t k = 0;
  auto add = [&](uint8_t kind, double seconds) {
    uint32_t us = (uint32_t)std::llround(seconds * 1e6);
    if (us == 0) return;
    t.shape |= (uint8_t)(kind << (2 * k));
    t.durations[k++] = us;
  };
  add(maxl_fw::phase::ACCELERATE, (vp - ve) / a);
  if (vp > 0) add(maxl_fw::phase::CRUISE, dCruise / vp);
  add(maxl_fw::phase::DECELERATE, (vp - vx) / a);
  t.phaseCount = k;
  t.alpha = (float)(a / L);
  return t;
}

uint32_t durationOf(const maxl_fw::msg::TimingSegment& t) {
  uint32_t total = 0;
  for (int k = 0; k < t.phaseCount; k++) total += t.durations[k];
  return total;
}

double exitSpeed(const maxl_fw::msg::TimingSegment& t, double length) {
  double T = durationOf(t) * 1e-6, q = 0, rest = 0, sum = 0;
  for (int k = t.phaseCount - 1; k >= 0; k--) {
    int kind = (t.shape >> (2 * k)) & 3;
    int c = kind == 1 ? 1 : kind == 3 ? -1 : 0;
    double d = t.durations[k] * 1e-6;
    q += c * d * (d / 2 + rest);
    rest += d;
    sum += c * d;
  }
  double nu0 = (1 - t.alpha * q) / T;
  return length * (nu0 + t.alpha * sum);
}

Bytes Author::helloRequest(uint8_t protocol) {
  seq = 0;
  return frame(seq++, maxl_fw::type::HELLO_REQUEST, [&](maxl_fw::ByteWriter& w) { w.u8(protocol); });
}
Bytes Author::ping(uint16_t pingId, uint16_t replyAfter) {
  return frame(seq++, maxl_fw::type::PING_REQUEST, [&](maxl_fw::ByteWriter& w) { maxl_fw::msg::write(w, maxl_fw::msg::Ping{pingId, replyAfter}); });
}
Bytes Author::clock(uint32_t deviceRef, uint32_t authorRef, int32_t ratePpb) {
  return frame(seq++, maxl_fw::type::CLOCK,
               [&](maxl_fw::ByteWriter& w) { maxl_fw::msg::write(w, maxl_fw::msg::Clock{deviceRef, authorRef, ratePpb}); });
}
Bytes Author::subscribe(uint8_t reader, uint8_t kind, uint8_t slot) {
  return frame(seq++, maxl_fw::type::SUBSCRIBE,
               [&](maxl_fw::ByteWriter& w) { maxl_fw::msg::write(w, maxl_fw::msg::Subscribe{reader, kind, slot}); });
}
Bytes Author::geometry(uint16_t firstId, const std::vector<int32_t>* p0, const std::vector<GeometrySegment>& segments,
                       uint8_t P) {
  std::vector<float> lengths;
  std::vector<int32_t> p1;
  for (auto& s : segments) {
    lengths.push_back(s.length);
    for (uint8_t i = 0; i < P; i++) p1.push_back(s.p1.at(i));
  }
  uint8_t flags = p0 ? maxl_fw::GEOMETRY_HAS_P0 : 0;
  return frame(seq++, maxl_fw::type::GEOMETRY, [&](maxl_fw::ByteWriter& w) {
    maxl_fw::msg::writeGeometry(w, firstId, (uint8_t)segments.size(), flags, P, p0 ? p0->data() : nullptr,
                             lengths.data(), p1.data());
  });
}
Bytes Author::timing(uint16_t firstId, float stopDecel, const uint32_t* start,
                     const std::vector<maxl_fw::msg::TimingSegment>& segments) {
  uint8_t flags = start ? maxl_fw::TIMING_HAS_START : 0;
  return frame(seq++, maxl_fw::type::TIMING, [&](maxl_fw::ByteWriter& w) {
    maxl_fw::msg::writeTiming(w, firstId, (uint8_t)segments.size(), flags, stopDecel, start ? *start : 0,
                           segments.data());
  });
}
Bytes Author::events(uint16_t segmentId, uint8_t slot, uint16_t firstIndex,
                     const std::vector<maxl_fw::msg::EventEntry>& entries) {
  return frame(seq++, maxl_fw::type::EVENTS, [&](maxl_fw::ByteWriter& w) {
    maxl_fw::msg::writeEvents(w, segmentId, slot, firstIndex, (uint8_t)entries.size(), entries.data());
  });
}
Bytes Author::replaceTail(uint16_t fromId) {
  return frame(seq++, maxl_fw::type::REPLACE_TAIL,
               [&](maxl_fw::ByteWriter& w) { maxl_fw::msg::write(w, maxl_fw::msg::ReplaceTail{fromId}); });
}
Bytes Author::halt(uint8_t mode, uint32_t at) {
  return frame(seq++, maxl_fw::type::HALT, [&](maxl_fw::ByteWriter& w) { maxl_fw::msg::write(w, maxl_fw::msg::Halt{mode, at}); });
}
Bytes Author::statusRequest() {
  return frame(seq++, maxl_fw::type::STATUS_REQUEST, [](maxl_fw::ByteWriter&) {});
}
Bytes Author::raw(uint8_t type, const Bytes& payload) {
  return frame(seq++, type, [&](maxl_fw::ByteWriter& w) {
    for (uint8_t b : payload) w.u8(b);
  });
}

}  // namespace maxltest
