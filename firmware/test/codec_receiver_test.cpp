// The streaming frame receiver (protocol §3 "Errors while receiving").
#include <gtest/gtest.h>

#include "maxl/wire/crc16.h"
#include "maxl/wire/frame_receiver.h"
#include "maxl/wire/frame_writer.h"
#include "support/hex.h"

using namespace maxl_fw;
using maxltest::fromHex;

namespace {
struct Outcome {
  int packets = 0;
  int errors = 0;
  CodecError lastError = CODEC_OK;
  std::vector<uint8_t> payload;
  uint8_t seq = 0, type = 0;
  uint32_t arrivedAt = 0;
};

Outcome feed(FrameReceiver& rx, const std::vector<uint8_t>& bytes, uint32_t t0 = 0) {
  Outcome o;
  for (size_t i = 0; i < bytes.size(); i++) {
    FrameReceiver::Result r = rx.push(bytes[i], t0 + (uint32_t)i);
    if (r == FrameReceiver::PACKET) {
      o.packets++;
      o.seq = rx.seq();
      o.type = rx.type();
      o.payload.assign(rx.payload(), rx.payload() + rx.payloadLength());
      o.arrivedAt = rx.arrivedAt();
    } else if (r == FrameReceiver::ERROR) {
      o.errors++;
      o.lastError = rx.error();
    }
  }
  return o;
}

std::vector<uint8_t> frameOf(uint8_t seq, uint8_t type, const std::vector<uint8_t>& payload) {
  OwnedFrameWriter w;
  ByteWriter& b = w.begin(seq, type);
  for (uint8_t x : payload) b.u8(x);
  EXPECT_TRUE(w.finish());
  return std::vector<uint8_t>(w.frame(), w.frame() + w.frameLength());
}
}  // namespace

TEST(FrameReceiver, DeliversAPacketAndItsArrivalTime) {
  OwnedFrameReceiver rx;
  auto f = frameOf(5, 0x02, {0x02, 0x01});
  Outcome o = feed(rx, f, 1000);
  EXPECT_EQ(o.packets, 1);
  EXPECT_EQ(o.errors, 0);
  EXPECT_EQ(o.seq, 5);
  EXPECT_EQ(o.type, 0x02);
  EXPECT_EQ(o.payload, (std::vector<uint8_t>{0x02, 0x01}));
  EXPECT_EQ(o.arrivedAt, 1000 + f.size() - 1);  // the delimiter's time
}

TEST(FrameReceiver, PayloadsWithZerosAndTheLargestPacket) {
  OwnedFrameReceiver rx;
  std::vector<uint8_t> zeros(60, 0);
  Outcome a = feed(rx, frameOf(0, 0, zeros));
  EXPECT_EQ(a.packets, 1);
  EXPECT_EQ(a.payload, zeros);
  std::vector<uint8_t> full(60);
  for (int i = 0; i < 60; i++) full[i] = (uint8_t)(i * 37 + 1);
  auto f = frameOf(255, 0x7F, full);
  EXPECT_EQ(f.size(), 66u);  // 64-byte packet: 65 encoded + delimiter
  Outcome b = feed(rx, f);
  EXPECT_EQ(b.packets, 1);
  EXPECT_EQ(b.payload, full);
}

TEST(FrameReceiver, EmptyFramesAreIgnored) {
  OwnedFrameReceiver rx;
  Outcome o = feed(rx, {0, 0, 0});
  EXPECT_EQ(o.packets + o.errors, 0);
}

TEST(FrameReceiver, TooLongThenRecovers) {
  OwnedFrameReceiver rx;
  std::vector<uint8_t> junk(66, 0x42);
  junk.push_back(0);
  auto good = frameOf(1, 2, {3});
  junk.insert(junk.end(), good.begin(), good.end());
  Outcome o = feed(rx, junk);
  EXPECT_EQ(o.errors, 1);
  EXPECT_EQ(o.lastError, CODEC_TOO_LONG);
  EXPECT_EQ(o.packets, 1);
}

TEST(FrameReceiver, SixtyFiveEncodedBytesAreNotTooLong) {
  OwnedFrameReceiver rx;
  // 65 encoded bytes that are a valid COBS frame but carry a bad CRC.
  std::vector<uint8_t> f(1, 65);
  for (int i = 0; i < 64; i++) f.push_back(0x11);
  f.push_back(0);
  Outcome o = feed(rx, f);
  EXPECT_EQ(o.lastError, CODEC_BAD_CRC);
}

TEST(FrameReceiver, CodePastTheEndIsBadCobs) {
  OwnedFrameReceiver rx;
  Outcome o = feed(rx, fromHex("0511220000"));
  EXPECT_EQ(o.errors, 1);
  EXPECT_EQ(o.lastError, CODEC_BAD_COBS);
}

TEST(FrameReceiver, ShortPacketsAreTooShort) {
  OwnedFrameReceiver rx;
  EXPECT_EQ(feed(rx, fromHex("0103010200")).lastError, CODEC_TOO_SHORT);  // 3 bytes: 00 01 02
  EXPECT_EQ(feed(rx, fromHex("0100")).lastError, CODEC_TOO_SHORT);        // 0 bytes
}

TEST(FrameReceiver, CorruptionIsBadCrc) {
  OwnedFrameReceiver rx;
  auto f = frameOf(9, 4, {1, 2, 3});
  for (size_t i = 0; i + 1 < f.size(); i++) {
    for (uint8_t bit = 1; bit; bit <<= 1) {
      auto g = f;
      g[i] ^= bit;
      if (g[i] == 0) continue;  // would split the frame instead
      Outcome o = feed(rx, g);
      EXPECT_EQ(o.packets, 0) << "byte " << i << " bit " << (int)bit;
      rx.reset();
    }
  }
}
