// CRC-16/CCITT-FALSE, COBS and the little-endian/varint readers (protocol §2, §3).
#include <gtest/gtest.h>

#include <random>

#include "maxl/wire/bytes.h"
#include "maxl/wire/cobs.h"
#include "maxl/wire/crc16.h"
#include "support/hex.h"

using namespace maxl_fw;
using maxltest::fromHex;
using maxltest::toHex;

TEST(Crc16, CheckValueOf123456789) {
  const char* s = "123456789";
  EXPECT_EQ(crc16((const uint8_t*)s, 9), 0x29B1);
}

TEST(Crc16, EmptyIsTheInitialValue) { EXPECT_EQ(crc16(nullptr, 0), 0xFFFF); }

TEST(Crc16, ByteWiseFormEqualsBitSerialDivision) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 2000; trial++) {
    uint8_t data[64];
    uint8_t n = (uint8_t)(rng() % 65);
    for (uint8_t i = 0; i < n; i++) data[i] = (uint8_t)rng();
    uint16_t slow = 0xFFFF;
    for (uint8_t i = 0; i < n; i++) {
      slow ^= (uint16_t)(data[i] << 8);
      for (int b = 0; b < 8; b++) slow = (slow & 0x8000) ? (uint16_t)((slow << 1) ^ 0x1021) : (uint16_t)(slow << 1);
    }
    ASSERT_EQ(crc16(data, n), slow);
  }
}

namespace {
std::string encode(const std::string& hex) {
  std::vector<uint8_t> in = fromHex(hex);
  std::vector<uint8_t> buf(in.size() + 2);
  std::copy(in.begin(), in.end(), buf.begin() + 1);
  uint8_t n = cobsEncodeInPlace(buf.data(), (uint8_t)in.size());
  return toHex(buf.data(), n);
}
}  // namespace

// The examples of Cheshire and Baker's paper (and Wikipedia's COBS page).
TEST(Cobs, KnownEncodings) {
  EXPECT_EQ(encode("00"), "0101");
  EXPECT_EQ(encode("0000"), "010101");
  EXPECT_EQ(encode("11220033"), "0311220233");
  EXPECT_EQ(encode("11223344"), "0511223344");
  EXPECT_EQ(encode("11000000"), "0211010101");
  EXPECT_EQ(encode(""), "01");
}

TEST(Cobs, RoundTripsRandomPacketsInPlace) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 5000; trial++) {
    uint8_t n = (uint8_t)(rng() % 65);
    std::vector<uint8_t> data(n);
    for (auto& b : data) b = (rng() % 4 == 0) ? 0 : (uint8_t)rng();
    std::vector<uint8_t> buf(n + 2);
    std::copy(data.begin(), data.end(), buf.begin() + 1);
    uint8_t encoded = cobsEncodeInPlace(buf.data(), n);
    ASSERT_EQ(encoded, n + 1);  // one byte of overhead under 254 bytes
    for (uint8_t i = 0; i < encoded; i++) ASSERT_NE(buf[i], 0);
    uint8_t out[64];
    int16_t decoded = cobsDecode(buf.data(), encoded, out, 64);
    ASSERT_EQ(decoded, n);
    ASSERT_TRUE(std::equal(data.begin(), data.end(), out));
  }
}

TEST(Cobs, DecodeRejectsACodePastTheEnd) {
  uint8_t bad[] = {0x05, 0x11, 0x22};
  uint8_t out[8];
  EXPECT_EQ(cobsDecode(bad, 3, out, 8), -1);
}

TEST(Bytes, LittleEndianIntegersAndFloats) {
  uint8_t buf[16];
  ByteWriter w(buf, 16);
  w.u16(0x1234);
  w.u32(0xA1B2C3D4);
  w.i32(-2);
  w.f32(1.5f);
  EXPECT_FALSE(w.failed());
  EXPECT_EQ(toHex(buf, w.length()), "3412d4c3b2a1feffffff0000c03f");
  ByteReader r(buf, w.length());
  EXPECT_EQ(r.u16(), 0x1234);
  EXPECT_EQ(r.u32(), 0xA1B2C3D4u);
  EXPECT_EQ(r.i32(), -2);
  EXPECT_EQ(r.f32(), 1.5f);
  EXPECT_TRUE(r.atEnd());
}

TEST(Bytes, ReadingPastTheEndFailsAndStaysFailed) {
  uint8_t buf[3] = {1, 2, 3};
  ByteReader r(buf, 3);
  EXPECT_EQ(r.u16(), 0x0201);
  EXPECT_EQ(r.u16(), 0);
  EXPECT_TRUE(r.failed());
  EXPECT_EQ(r.u8(), 0);
  EXPECT_FALSE(r.atEnd());
}

TEST(Bytes, WritingPastTheEndFails) {
  uint8_t buf[3];
  ByteWriter w(buf, 3);
  w.u16(1);
  w.u16(2);
  EXPECT_TRUE(w.failed());
}

TEST(Varint, EncodesLeb128) {
  struct Case {
    uint32_t v;
    const char* hex;
  } cases[] = {{0, "00"}, {1, "01"}, {127, "7f"}, {128, "8001"}, {300, "ac02"}, {16384, "808001"},
               {0xFFFFFFFFu, "ffffffff0f"}};
  for (auto& c : cases) {
    uint8_t buf[8];
    ByteWriter w(buf, 8);
    w.varint(c.v);
    EXPECT_EQ(toHex(buf, w.length()), c.hex);
    EXPECT_EQ(ByteWriter::varintSize(c.v), w.length());
    ByteReader r(buf, w.length());
    EXPECT_EQ(r.varint(), c.v);
    EXPECT_TRUE(r.atEnd());
  }
}

TEST(Varint, SixBytesOrOverU32AreMalformed) {
  std::vector<uint8_t> six = fromHex("808080808001");
  ByteReader a(six.data(), (uint8_t)six.size());
  a.varint();
  EXPECT_TRUE(a.failed());
  std::vector<uint8_t> big = fromHex("ffffffff1f");  // 2^33 - 1
  ByteReader b(big.data(), (uint8_t)big.size());
  b.varint();
  EXPECT_TRUE(b.failed());
  std::vector<uint8_t> truncated = fromHex("8080");
  ByteReader c(truncated.data(), (uint8_t)truncated.size());
  c.varint();
  EXPECT_TRUE(c.failed());
}
