// Payload layouts: round trips, exact lengths, structural checks.
#include <gtest/gtest.h>

#include "maxl/wire/messages.h"

using namespace maxl_fw;

namespace {
template <class M>
std::vector<uint8_t> bytesOf(const M& m) {
  uint8_t buf[64];
  ByteWriter w(buf, 60);
  msg::write(w, m);
  EXPECT_FALSE(w.failed());
  return std::vector<uint8_t>(buf, buf + w.length());
}
}  // namespace

TEST(Messages, FixedSizesMatchTheSpec) {
  EXPECT_EQ(bytesOf(msg::HelloRequest{1}).size(), 1u);
  EXPECT_EQ(bytesOf(msg::Ping{1, 0}).size(), 4u);
  EXPECT_EQ(bytesOf(msg::Clock{1, 2, 3}).size(), 12u);
  EXPECT_EQ(bytesOf(msg::Subscribe{1, 2, 3}).size(), 3u);
  EXPECT_EQ(bytesOf(msg::ReplaceTail{1}).size(), 2u);
  EXPECT_EQ(bytesOf(msg::Halt{1, 2}).size(), 5u);
  EXPECT_EQ(bytesOf(msg::Ack{1, 2, 3}).size(), 3u);
  EXPECT_EQ(bytesOf(msg::Nack{1, 2, 3}).size(), 4u);
  EXPECT_EQ(bytesOf(msg::Pong{1, 2, 3}).size(), 10u);
  EXPECT_EQ(bytesOf(msg::Status{1, 2, 3, 0.5f, 4, 5}).size(), 13u);
}

TEST(Messages, WrongLengthsAreMalformed) {
  msg::DecodeContext ctx{0, 0};
  uint8_t buf[20] = {0};
  EXPECT_EQ(msg::checkPayload(type::PING_REQUEST, buf, 4, ctx), CODEC_OK);
  EXPECT_EQ(msg::checkPayload(type::PING_REQUEST, buf, 2, ctx), CODEC_MALFORMED);
  EXPECT_EQ(msg::checkPayload(type::PING_REQUEST, buf, 5, ctx), CODEC_MALFORMED);
  EXPECT_EQ(msg::checkPayload(type::STATUS_REQUEST, buf, 0, ctx), CODEC_OK);
  EXPECT_EQ(msg::checkPayload(type::STATUS_REQUEST, buf, 1, ctx), CODEC_MALFORMED);
  EXPECT_EQ(msg::checkPayload(type::HALT, buf, 5, ctx), CODEC_OK);
  EXPECT_EQ(msg::checkPayload(type::HALT, buf, 4, ctx), CODEC_MALFORMED);
}

TEST(Messages, UnknownTypes) {
  msg::DecodeContext ctx{0, 0};
  uint8_t buf[1] = {0};
  for (int t : {0x00, 0x0B, 0x20, 0x3F, 0x40, 0x48, 0x7F, 0x80, 0xFF})
    EXPECT_EQ(msg::checkPayload((uint8_t)t, buf, 0, ctx), CODEC_UNKNOWN_MESSAGE) << t;
}

TEST(Messages, GeometryLengthDependsOnPositionSlots) {
  uint8_t buf[64];
  ByteWriter w(buf, 60);
  int32_t p0[2] = {1, 2}, p1[4] = {3, 4, 5, 6};
  float lengths[2] = {1.0f, 2.0f};
  msg::writeGeometry(w, 10, 2, GEOMETRY_HAS_P0, 2, p0, lengths, p1);
  EXPECT_EQ(w.length(), 4 + 8 + 2 * 12);
  msg::GeometryView g;
  ASSERT_TRUE(g.parse(buf, w.length(), 2));
  EXPECT_EQ(g.firstId, 10);
  EXPECT_EQ(g.p0(1), 2);
  EXPECT_EQ(g.length(1), 2.0f);
  EXPECT_EQ(g.p1(1, 0), 5);
  EXPECT_EQ(g.p1(1, 1), 6);
  EXPECT_FALSE(g.parse(buf, w.length(), 1));
  EXPECT_FALSE(g.parse(buf, w.length(), 3));
  EXPECT_FALSE(g.parse(buf, (uint8_t)(w.length() - 1), 2));
}

TEST(Messages, ShapeBits) {
  EXPECT_EQ(msg::shapePhaseCount(0x00), -1);  // at least one phase
  EXPECT_EQ(msg::shapePhaseCount(0x01), 1);
  EXPECT_EQ(msg::shapePhaseCount(0x39), 3);  // accelerate, cruise, decelerate
  EXPECT_EQ(msg::shapePhaseCount(0x0E), 2);  // cruise, decelerate
  EXPECT_EQ(msg::shapePhaseCount(0x04), -1);  // a phase after NONE
  EXPECT_EQ(msg::shapePhaseCount(0x31), -1);  // phase 3 after NONE
  EXPECT_EQ(msg::shapePhaseCount(0x40), -1);  // bits 6-7
  EXPECT_EQ(msg::shapePhaseCount(0xFF), -1);
}

TEST(Messages, TimingRoundTrip) {
  msg::TimingSegment segs[2] = {};
  segs[0].shape = 0x39;
  segs[0].phaseCount = 3;
  segs[0].durations[0] = 1;
  segs[0].durations[1] = 300;
  segs[0].durations[2] = 70000;
  segs[0].alpha = 12.0f;
  segs[1].shape = 0x02;
  segs[1].phaseCount = 1;
  segs[1].durations[0] = 0xFFFFFFFFu;
  segs[1].alpha = 0.0f;
  uint8_t buf[64];
  ByteWriter w(buf, 60);
  msg::writeTiming(w, 7, 2, TIMING_HAS_START, 250.0f, 99, segs);
  msg::TimingView t;
  ASSERT_TRUE(t.parse(buf, w.length()));
  EXPECT_EQ(t.firstId, 7);
  EXPECT_EQ(t.start, 99u);
  EXPECT_EQ(t.stopDecel, 250.0f);
  msg::TimingSegment s;
  ASSERT_TRUE(t.next(s));
  EXPECT_EQ(s.durations[2], 70000u);
  ASSERT_TRUE(t.next(s));
  EXPECT_EQ(s.durations[0], 0xFFFFFFFFu);
  EXPECT_FALSE(t.parse(buf, (uint8_t)(w.length() + 1)));  // a byte left over
}

TEST(Messages, SamplesNeedTheChannelCount) {
  uint8_t buf[64];
  ByteWriter w(buf, 60);
  msg::writeSamplesHeader(w, 1, 2, 2, 1000);
  w.varint(0);
  w.f32(1.0f);
  w.f32(2.0f);
  w.varint(300);
  w.f32(3.0f);
  w.f32(4.0f);
  msg::SamplesView s;
  EXPECT_TRUE(s.parse(buf, w.length(), 2));
  EXPECT_FALSE(s.parse(buf, w.length(), 3));
  ASSERT_TRUE(s.parse(buf, w.length(), 2));
  uint32_t dt;
  float v[2];
  s.next(dt, v);
  s.next(dt, v);
  EXPECT_EQ(dt, 300u);
  EXPECT_EQ(v[1], 4.0f);
}

TEST(Messages, NamesLongerThan31AreMalformed) {
  uint8_t buf[64];
  ByteWriter w(buf, 60);
  w.u8(0);
  w.u8(1);
  w.u8(0);
  w.u8(32);
  for (int i = 0; i < 32; i++) w.u8('a');
  msg::Reader r;
  EXPECT_FALSE(msg::parse(buf, w.length(), r));
}
