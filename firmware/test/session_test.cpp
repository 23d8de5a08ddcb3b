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
  Answer a = h.exchange(h.author.raw(type::PING_REQUEST, {1, 0, 0, 0}));
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
  Answer a = h.exchange(h.author.raw(type::PING_REQUEST, {1, 0}));  // the old 2-byte PING
  EXPECT_EQ(a.reason, nack::MALFORMED);
  EXPECT_EQ(a.detail, type::PING_REQUEST);
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

TEST(Session, PongWaitsReplyAfterAndSaysWhenItLeft) {
  Harness h;
  h.open({});
  Bytes ping = h.author.ping(0x1234, 700);
  h.at(2000000);
  h.send(ping);
  std::vector<Packet> first = h.take();
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].type, type::ACK);  // acked now, answered later
  EXPECT_FALSE(h.device->idle());       // a PONG is waiting: keep looping
  h.at(2000699);
  h.loop();
  EXPECT_TRUE(h.take().empty());
  h.at(2000712);
  h.loop();
  std::vector<Packet> later = h.take();
  ASSERT_EQ(later.size(), 1u);
  ASSERT_EQ(later[0].type, type::PONG);
  msg::Pong pong;
  ASSERT_TRUE(msg::parse(later[0].payload.data(), (uint8_t)later[0].payload.size(), pong));
  EXPECT_EQ(pong.pingId, 0x1234);
  EXPECT_EQ(pong.rxTime, 2000000u);
  EXPECT_EQ(pong.txTime, 2000712u);  // when it really went
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

// The device's receive and transmit buffers are one (device.h): a STATUS due
// while a frame is half-received must wait, not overwrite it.
TEST(Session, FramesArrivingByteByByteSurviveStatusReports) {
  MAXL_TrackPositionLinear x("x", position);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  std::vector<int32_t> p0 = {0};
  std::vector<GeometrySegment> geometry;
  for (int k = 0; k < 6; k++) geometry.push_back({1.0f, {65536 * (k + 1)}});
  Bytes g = h.author.geometry(0, &p0, geometry, 1);
  msg::TimingSegment cruise{};
  cruise.shape = phase::CRUISE;
  cruise.phaseCount = 1;
  cruise.durations[0] = 300000;
  uint32_t start = 10000000;  // far ahead: running (waiting), so STATUS every 100 ms
  Bytes t0 = h.author.timing(0, 1000.0f, &start, {cruise, cruise});
  Bytes t1 = h.author.timing(2, 1000.0f, nullptr, {cruise, cruise, cruise});
  h.take();
  uint32_t now = 500;
  int statuses = 0;
  std::vector<Answer> answers;
  for (const Bytes* f : {&g, &t0, &t1}) {
    for (uint8_t b : *f) {  // one byte every 40 µs, a loop() after each
      now += 40;
      h.at(now);
      maxl_fw::host::pushRx(&b, 1);
      h.loop();
      for (const Packet& p : h.take()) {
        if (p.type == type::STATUS) statuses++;
        if (p.type == type::ACK || p.type == type::NACK) answers.push_back(answerOf(p));
      }
    }
    now += 99000;  // the next periodic STATUS falls due about 25 bytes into the next frame
  }
  ASSERT_EQ(answers.size(), 3u);
  for (const Answer& a : answers) EXPECT_EQ(a.reason, 0) << "seq " << (int)a.seq << " detail " << a.detail;
  EXPECT_GE(statuses, 1);
  EXPECT_EQ(h.device->motion().queue().timed(), 5);
}

// Paced reports (MAXL_TX_BYTES_PER_LOOP, on by default on AVR): a STATUS goes
// out a few bytes per loop(), and anything else that must be written, or a
// byte arriving, first finishes it.
TEST(Session, PacedStatusGoesOutInPiecesAndIsFlushedByTraffic) {
  MAXL_TrackPositionLinear x("x", position);
  Harness h;
  h.open({{0, kind::POSITION, 0}});
  std::vector<int32_t> p0 = {0};
  msg::TimingSegment cruise{};
  cruise.shape = phase::CRUISE;
  cruise.phaseCount = 1;
  cruise.durations[0] = 300000;
  uint32_t start = 10000000;
  EXPECT_EQ(h.exchange(h.author.geometry(0, &p0, {{1.0f, {65536}}}, 1)).reason, 0);
  EXPECT_EQ(h.exchange(h.author.timing(0, 1000.0f, &start, {cruise})).reason, 0);
  h.loop();
  h.take();
  // Running (waiting for the start): the next periodic STATUS, paced at 2 bytes per loop.
  h.device->setTransmitPacing(2);
  h.loopAt(h.now() + 100000);
  EXPECT_EQ(maxl_fw::host::txLength(), 2u);
  h.loop();
  EXPECT_EQ(maxl_fw::host::txLength(), 4u);
  EXPECT_FALSE(h.device->idle());
  // A frame arrives: the rest of the STATUS goes first, then the frame's
  // reply (another STATUS, paced too, finished by the ACK that follows it).
  h.send(h.author.statusRequest());
  std::vector<Packet> p = h.take();
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[0].type, type::STATUS);
  EXPECT_EQ(p[1].type, type::STATUS);
  EXPECT_EQ(p[2].type, type::ACK);
  msg::Status s;
  ASSERT_TRUE(msg::parse(p[0].payload.data(), (uint8_t)p[0].payload.size(), s));
  EXPECT_EQ(s.state, state::RUNNING);
  // Left alone, a paced frame finishes over the following loops.
  h.loopAt(h.now() + 100000);
  for (int i = 0; i < 20; i++) h.loop();
  p = h.take();
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].type, type::STATUS);
}
