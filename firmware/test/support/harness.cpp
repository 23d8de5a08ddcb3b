#include "support/harness.h"

#include <gtest/gtest.h>

#include "maxl/wire/frame_receiver.h"
#include "maxl/wire/messages.h"

namespace maxltest {

Harness::Harness(const char* name) {
  maxl_fw::host::reset();
  device.reset(new MAXL_Device(name));
  device->begin();
}

void Harness::send(const Bytes& frame) {
  size_t accepted = maxl_fw::host::pushRx(frame.data(), frame.size());
  EXPECT_EQ(accepted, frame.size());
  // loop() takes a bounded number of bytes per call: run until all are in.
  do loop();
  while (maxl_fw::host::rxPending() > 0);
}

std::vector<Packet> decodeFrames(const uint8_t* bytes, size_t n) {
  std::vector<Packet> out;
  maxl_fw::OwnedFrameReceiver rx;
  for (size_t i = 0; i < n; i++) {
    auto r = rx.push(bytes[i], 0);
    if (r == maxl_fw::FrameReceiver::PACKET) {
      Packet p;
      p.seq = rx.seq();
      p.type = rx.type();
      p.payload.assign(rx.payload(), rx.payload() + rx.payloadLength());
      out.push_back(p);
    } else if (r == maxl_fw::FrameReceiver::ERROR) {
      ADD_FAILURE() << "device sent a bad frame: " << maxl_fw::codecErrorName(rx.error());
    }
  }
  return out;
}

maxl_fw::msg::Status Harness::lastStatus() {
  maxl_fw::msg::Status s{};
  bool found = false;
  for (auto& p : take())
    if (p.type == maxl_fw::type::STATUS) found = maxl_fw::msg::parse(p.payload.data(), (uint8_t)p.payload.size(), s);
  EXPECT_TRUE(found);
  return s;
}

std::vector<Packet> Harness::take() {
  std::vector<Packet> out = decodeFrames(maxl_fw::host::tx(), maxl_fw::host::txLength());
  maxl_fw::host::clearTx();
  return out;
}

Answer answerOf(const Packet& p) {
  Answer a{};
  if (p.type == maxl_fw::type::ACK) {
    maxl_fw::msg::Ack m;
    EXPECT_TRUE(maxl_fw::msg::parse(p.payload.data(), (uint8_t)p.payload.size(), m));
    a.seq = m.ackSeq;
    a.freeSegments = m.freeSegments;
    a.freeEvents = m.freeEvents;
  } else if (p.type == maxl_fw::type::NACK) {
    maxl_fw::msg::Nack m;
    EXPECT_TRUE(maxl_fw::msg::parse(p.payload.data(), (uint8_t)p.payload.size(), m));
    a.seq = m.seq;
    a.reason = m.reason;
    a.detail = m.detail;
  }
  return a;
}

std::vector<Answer> Harness::answers() {
  std::vector<Answer> out;
  for (const Packet& p : take())
    if (p.type == maxl_fw::type::ACK || p.type == maxl_fw::type::NACK) out.push_back(answerOf(p));
  return out;
}

Answer Harness::exchange(const Bytes& frame) {
  take();
  send(frame);
  std::vector<Answer> a = answers();
  EXPECT_EQ(a.size(), 1u);
  return a.empty() ? Answer{0xFF, 0xFF, 0xFFFF, 0, 0} : a.back();
}

void Harness::open(const std::vector<std::vector<uint8_t>>& subscriptions) {
  Answer a = exchange(author.helloRequest());
  EXPECT_EQ(a.reason, 0);
  for (auto& s : subscriptions) {
    Answer b = exchange(author.subscribe(s.at(0), s.at(1), s.at(2)));
    EXPECT_EQ(b.reason, 0) << "subscribe reader " << (int)s.at(0);
  }
  take();
}

}  // namespace maxltest
