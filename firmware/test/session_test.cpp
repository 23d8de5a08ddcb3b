// Sessions and sequence numbers (protocol §3), HELLO/READER, PING/PONG, CLOCK.
#include <gtest/gtest.h>

#include "support/harness.h"

using namespace maxl_fw;
using namespace maxltest;

namespace {
void position(float, float) {}
void event(float) {}
}  // namespace

TEST(Session, NothingIsHandledBeforeHelloRequest) {
  Harness h;
  Answer a = h.exchange(h.author.raw(type::PING, {1, 0}));
  EXPECT_EQ(a.reason, nack::OUT_OF_ORDER);
  EXPECT_EQ(a.detail, nack::NO_SESSION_DETAIL);
}

TEST(Session, HelloRequestAnswersAckHelloAndReaders) {
  MAXL_TrackPositionLinear x("stepper", position);
  MAXL_TrackEvent power("laserPower", event);
  MAXL_SensorWriter accel("accel", 3);
  Harness h("motorOne");
  h.send(h.author.helloRequest());
  std::vector<Packet> p = h.take();
  ASSERT_EQ(p.size(), 5u);
  EXPECT_EQ(p[0].type, type::ACK);
  EXPECT_EQ(answerOf(p[0]).seq, 0);
  EXPECT_EQ(answerOf(p[0]).freeSegments, MAXL_SEGMENT_CAPACITY);
  EXPECT_EQ(answerOf(p[0]).freeEvents, MAXL_EVENT_CAPACITY);
  ASSERT_EQ(p[1].type, type::HELLO);
  msg::Hello hello;
  ASSERT_TRUE(msg::parse(p[1].payload.data(), (uint8_t)p[1].payload.size(), hello));
  EXPECT_EQ(hello.protocol, 1);
  EXPECT_EQ(hello.clockHz, 1000000u);
  EXPECT_EQ(hello.segmentCapacity, MAXL_SEGMENT_CAPACITY);
  EXPECT_EQ(hello.readerCount, 3);
  EXPECT_EQ(std::string(hello.name.text, hello.name.length), "motorOne");
  const char* names[] = {"stepper", "laserPower", "accel"};
  const uint8_t kinds[] = {kind::POSITION, kind::EVENT, kind::SENSOR};
  for (int i = 0; i < 3; i++) {
    ASSERT_EQ(p[2 + i].type, type::READER);
    msg::Reader r;
    ASSERT_TRUE(msg::parse(p[2 + i].payload.data(), (uint8_t)p[2 + i].payload.size(), r));
    EXPECT_EQ(r.index, i);
    EXPECT_EQ(r.kind, kinds[i]);
    EXPECT_EQ(r.channels, i == 2 ? 3 : 0);
    EXPECT_EQ(std::string(r.name.text, r.name.length), names[i]);
  }
  // Device frames carry the device's own counter.
  EXPECT_EQ(p[1].seq, (uint8_t)(p[0].seq + 1));
}

TEST(Session, VersionMismatchStillSaysHello) {
  Harness h;
  h.send(h.author.helloRequest(2));
  std::vector<Packet> p = h.take();
  ASSERT_EQ(p.size(), 2u);
  Answer a = answerOf(p[0]);
  EXPECT_EQ(a.reason, nack::VERSION_MISMATCH);
  EXPECT_EQ(a.detail, 1);
  EXPECT_EQ(p[1].type, type::HELLO);
}

TEST(Session, InOrderFramesAreAckedAndExpectedAdvances) {
  Harness h;
  h.open({});
  for (int i = 0; i < 300; i++) {  // across the u8 wrap of seq
    Answer a = h.exchange(h.author.raw(type::STATUS_REQUEST, {}));
    EXPECT_EQ(a.reason, 0);
    EXPECT_EQ(a.seq, (uint8_t)(i + 1));
  }
}

TEST(Session, OutOfOrderIsNackedWithTheExpectedSeq) {
  Harness h;
  h.open({});
  h.author.seq = 5;  // skips 1..4
  Answer a = h.exchange(h.author.raw(type::STATUS_REQUEST, {}));
  EXPECT_EQ(a.reason, nack::OUT_OF_ORDER);
  EXPECT_EQ(a.seq, 5);
  EXPECT_EQ(a.detail, 1);
}

TEST(Session, DuplicatesAreAnsweredAgainNotHandled) {
  Harness h;
  MAXL_TrackEvent ev("e", event);
  h.open({});
  Bytes sub = h.author.subscribe(0, kind::EVENT, 0);  // seq 1
  EXPECT_EQ(h.exchange(sub).reason, 0);
  Bytes bad = h.author.subscribe(0, kind::POSITION, 0);  // seq 2: wrong kind
  Answer first = h.exchange(bad);
  EXPECT_EQ(first.reason, nack::BAD_SUBSCRIPTION);
  // The nack was "lost"; the author resends from seq 1.
  Answer again1 = h.exchange(sub);
  EXPECT_EQ(again1.reason, 0);
  EXPECT_EQ(again1.seq, 1);
  Answer again2 = h.exchange(bad);
  EXPECT_EQ(again2.reason, nack::BAD_SUBSCRIPTION);  // the same answer, not an ack
  EXPECT_EQ(again2.seq, 2);
  // ... and the next new frame is still seq 3.
  Answer next = h.exchange(h.author.raw(type::STATUS_REQUEST, {}));
  EXPECT_EQ(next.reason, 0);
  EXPECT_EQ(next.seq, 3);
}

TEST(Session, SeqsBeforeTheSessionAreNotDuplicates) {
  Harness h;
  h.open({});
  h.author.seq = 250;  // "16 before expected" but never seen in this session
  Answer a = h.exchange(h.author.raw(type::STATUS_REQUEST, {}));
  EXPECT_EQ(a.reason, nack::OUT_OF_ORDER);
  EXPECT_EQ(a.detail, 1);
}

TEST(Session, BadFramesGetBadCrcWithTheExpectedSeq) {
  Harness h;
  h.open({});
  Bytes f = h.author.raw(type::STATUS_REQUEST, {});
  f[1] ^= 0x40;
  Answer a = h.exchange(f);
  EXPECT_EQ(a.reason, nack::BAD_CRC);
  EXPECT_EQ(a.seq, 1);
  EXPECT_EQ(a.detail, 0);
  // TOO_LONG: silence. Empty frames: silence.
  h.take();
  Bytes junk(80, 0x55);
  junk.push_back(0);
  junk.push_back(0);
  h.send(junk);
  EXPECT_TRUE(h.take().empty());
}

TEST(Session, MalformedAndUnknownAdvanceExpected) {
  Harness h;
  h.open({});
  Answer a = h.exchange(h.author.raw(type::PING, {1}));
  EXPECT_EQ(a.reason, nack::MALFORMED);
  EXPECT_EQ(a.detail, type::PING);
  Answer b = h.exchange(h.author.raw(0x30, {}));
  EXPECT_EQ(b.reason, nack::UNKNOWN_MESSAGE);
  EXPECT_EQ(b.detail, 0x30);
  Answer c = h.exchange(h.author.raw(type::ACK, {0, 0, 0}));  // device-to-author type
  EXPECT_EQ(c.reason, nack::UNKNOWN_MESSAGE);
  Answer d = h.exchange(h.author.raw(type::STATUS_REQUEST, {}));
  EXPECT_EQ(d.reason, 0);
  EXPECT_EQ(d.seq, 4);
}

TEST(Session, PongStampsTheDelimiterArrival) {
  Harness h;
  h.open({});
  Bytes ping = h.author.ping(0xBEEF);
  h.at(1000000);
  // All but the delimiter arrive at 1 000 000; the delimiter at 1 000 250.
  maxl_fw::host::pushRx(ping.data(), ping.size() - 1);
  h.loop();
  h.at(1000250);
  h.send(Bytes{0});
  std::vector<Packet> p = h.take();
  ASSERT_EQ(p.size(), 2u);
  ASSERT_EQ(p[0].type, type::PONG);  // PONG first, then the ACK
  msg::Pong pong;
  ASSERT_TRUE(msg::parse(p[0].payload.data(), (uint8_t)p[0].payload.size(), pong));
  EXPECT_EQ(pong.pingId, 0xBEEF);
  EXPECT_EQ(pong.rxTime, 1000250u);
  EXPECT_EQ(pong.txTime, 1000250u);
  EXPECT_EQ(p[1].type, type::ACK);
}

TEST(Session, ClockGivesMachineTime) {
  Harness h;
  h.open({});
  EXPECT_FALSE(h.device->clockKnown());
  h.at(5000000);
  EXPECT_EQ(h.device->machineTime(), 5000000u);
  // author = 4e9 + (device − 1e6)·(1 + 1000 ppm)
  EXPECT_EQ(h.exchange(h.author.clock(1000000, 4000000000u, 1000000)).reason, 0);
  EXPECT_TRUE(h.device->clockKnown());
  EXPECT_EQ(h.device->machineTimeAt(1000000), 4000000000u);
  EXPECT_EQ(h.device->machineTimeAt(3000000), 4000000000u + 2000000u + 2000u);
  EXPECT_EQ(h.device->machineTimeAt(0), 4000000000u - 1000000u - 1000u);
  // wraps at 2^32
  EXPECT_EQ(h.device->machineTimeAt(301000000), (uint32_t)(4000000000ull + 300000000ull + 300000ull));
}

TEST(Session, HelloRequestDropsSubscriptions) {
  MAXL_TrackEvent ev("e", event);
  Harness h;
  h.open({{0, kind::EVENT, 2}});
  EXPECT_TRUE(ev.subscribed());
  EXPECT_EQ(ev.slot(), 2);
  h.exchange(h.author.helloRequest());
  EXPECT_FALSE(ev.subscribed());
}
