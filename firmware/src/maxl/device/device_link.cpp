// MAXL_Device: bytes in and out, sequence numbers, and the replies that are
// not specific to one handler (ACK, NACK, HELLO, READER, STATUS, SAMPLES).
#include "maxl/device/device.h"

#include "maxl/readers/reader.h"
#include "maxl/time/wrap.h"
#include "maxl/wire/messages.h"

using namespace maxl_fw;

namespace {
// Most bytes taken from the link in one loop(). More than Arduino's 64-byte
// receive ring holds, so that one pass empties it even while bytes keep coming
// (25 a ms at 250 000 baud); bounded, so that a link that never pauses cannot
// hold loop() (and everything else it runs) for ever.
const uint8_t BYTES_PER_LOOP = 96;
}  // namespace

// Reads what the link holds (up to BYTES_PER_LOOP) and handles every frame
// that ends in it. Taking one frame per loop() lost bytes: a loop() longer than
// the ring's 2.6 ms (steps being planned) while short frames stream in let the
// ring overflow. It stops after a frame only while something waits for the
// frame buffer, which is also the transmit buffer (device.h): a STATUS due, or
// a PONG due, so that loop() sends it between two frames.
void MAXL_Device::pollLink() {
  for (uint8_t i = 0; i < BYTES_PER_LOOP; i++) {
    int16_t b = hal::readByte();
    if (b < 0) return;
    if (!MAXL_TX_BUFFER) flushTransmit();  // the byte will land in the buffer a paced frame is in
    // PONG.rxTime is the clock when the delimiter was read.
    FrameReceiver::Result r = rx_.push((uint8_t)b, b == 0 ? clockNow() : 0);
    if (r == FrameReceiver::PACKET)
      onPacket();
    else if (r == FrameReceiver::ERROR)
      onFrameError(rx_.error());
    else
      continue;
    if (statusPending_ || (pongPending_ && timeDiff(clockNow(), pongDueAt_) >= 0)) return;
  }
}

// §3: nothing is said about a frame too long to be one of ours; anything
// else that cannot be trusted gets BAD_CRC with the seq the device expects.
void MAXL_Device::onFrameError(CodecError error) {
  if (error == CODEC_TOO_LONG) return;
  msg::Nack n = {session_.expected(), nack::BAD_CRC, 0};
  msg::write(beginFrame(type::NACK), n);
  sendFrame();
}

void MAXL_Device::onPacket() {
  uint8_t seq = rx_.seq();
  uint8_t t = rx_.type();
  const uint8_t* p = rx_.payload();
  uint8_t n = rx_.payloadLength();

  if (t == type::HELLO_REQUEST) {
    msg::HelloRequest m;
    if (msg::parse(p, n, m)) {
      startSession(seq, m.protocol);
      return;
    }
  }
  switch (session_.classify(seq)) {
    case Session::NO_SESSION:
      sendAnswer(seq, nack::OUT_OF_ORDER, nack::NO_SESSION_DETAIL);
      return;
    case Session::OUT_OF_ORDER:
      sendAnswer(seq, nack::OUT_OF_ORDER, session_.expected());
      return;
    case Session::DUPLICATE: {
      uint8_t reason;
      uint16_t detail;
      session_.answerTo(seq, reason, detail);
      sendAnswer(seq, reason, detail);
      return;
    }
    case Session::NEW:
      break;
  }
  readClock();
  motion_.tick(now_);
  Answer a = handle(t, p, n);
  session_.record(a.reason, a.detail);
  sendAnswer(seq, a.reason, a.detail);
}

// HELLO_REQUEST: a new session whatever `expected` was (§4). The answer is
// ACK, HELLO, then one READER per reader; with another protocol version, a
// VERSION_MISMATCH nack and HELLO only.
void MAXL_Device::startSession(uint8_t seq, uint8_t protocol) {
  resetSession();
  session_.start();
  lastStatusAt_ = now_ = clockNow();
  if (protocol != PROTOCOL_VERSION) {
    session_.record(nack::VERSION_MISMATCH, PROTOCOL_VERSION);
    sendAnswer(seq, nack::VERSION_MISMATCH, PROTOCOL_VERSION);
    sendHello();
    return;
  }
  session_.record(0, 0);
  sendAnswer(seq, 0, 0);
  sendHello();
  uint8_t count = MAXL_Reader::count();
  for (uint8_t i = 0; i < count; i++) sendReader(i);
}

void MAXL_Device::sendAnswer(uint8_t seq, uint8_t reason, uint16_t detail) {
  if (reason == 0) {
    msg::Ack a = {seq, motion_.queue().free(), events_.free()};
    msg::write(beginFrame(type::ACK), a);
  } else {
    msg::Nack n = {seq, reason, detail};
    msg::write(beginFrame(type::NACK), n);
  }
  sendFrame();
}

namespace {
msg::Name nameOf(const char* s) {
  msg::Name n;
  n.text = s ? s : "";
  n.length = 0;
  while (n.text[n.length] && n.length < MAX_NAME) n.length++;
  return n;
}
}  // namespace

void MAXL_Device::sendHello() {
  msg::Hello h;
  h.protocol = PROTOCOL_VERSION;
  h.fwMajor = MAXL_FW_MAJOR;
  h.fwMinor = MAXL_FW_MINOR;
  h.fwPatch = MAXL_FW_PATCH;
  h.clockHz = CLOCK_HZ;
  h.segmentCapacity = MAXL_SEGMENT_CAPACITY;
  h.eventCapacity = MAXL_EVENT_CAPACITY;
  h.readerCount = MAXL_Reader::count();
  h.name = nameOf(name_);
  msg::write(beginFrame(type::HELLO), h);
  sendFrame();
}

void MAXL_Device::sendReader(uint8_t index) {
  MAXL_Reader* r = MAXL_Reader::at(index);
  if (!r) return;
  msg::Reader m;
  m.index = index;
  m.kind = r->kind();
  m.channels = r->channels();
  m.name = nameOf(r->name());
  msg::write(beginFrame(type::READER), m);
  sendFrame();
}

// The PONG of the last ping: at once from a handler (`paced` false: the frame
// buffer is free once the ping was parsed), or from loop() when its reply time
// has come, paced out like STATUS.
void MAXL_Device::sendPong(bool paced) {
  msg::Pong pong = {pongId_, pongReceivedAt_, clockNow()};
  msg::write(beginFrame(type::PONG), pong);
  if (paced) sendFramePaced();
  else sendFrame();
  pongPending_ = false;
}

void MAXL_Device::sendStatus() {
  msg::Status s;
  s.now = now_;
  s.state = motion_.statusState();
  motion_.where(now_, s.segmentId, s.sigma);
  s.depth = motion_.queue().count();
  s.flags = flags_;
  msg::write(beginFrame(type::STATUS), s);
  sendFramePaced();
  lastStatusAt_ = now_;
  statusPending_ = false;
}

bool MAXL_Device::sendSamples(uint8_t reader, uint16_t sampleSeq, uint8_t count, uint32_t t0, const uint8_t* bytes,
                              uint8_t length) {
  if (receivingIntoTxBuffer()) return false;  // the buffer holds a frame being received
  ByteWriter& w = beginFrame(type::SAMPLES);
  msg::writeSamplesHeader(w, reader, sampleSeq, count, t0);
  for (uint8_t i = 0; i < length; i++) w.u8(bytes[i]);
  sendFramePaced();
  return true;
}

// Every frame is built in frameBuffer_, so a paced frame still going out is
// finished first.
ByteWriter& MAXL_Device::beginFrame(uint8_t t) {
  flushTransmit();
  return tx_.begin(txSeq_++, t);
}

void MAXL_Device::sendFrame() {
  if (tx_.finish()) hal::write(tx_.frame(), tx_.frameLength());
}

// Unsolicited frames (STATUS, SAMPLES) leave MAXL_TX_BYTES_PER_LOOP bytes per
// loop(), so that no single loop() spends the ~100 µs a whole frame costs on
// an AVR (steps would come late).
void MAXL_Device::sendFramePaced() {
  if (!tx_.finish()) return;
  txSent_ = 0;
  txLength_ = tx_.frameLength();
  pumpTransmit();
}

void MAXL_Device::pumpTransmit() {
  if (!txLength_) return;
  uint8_t n = txPacing_ ? txPacing_ : txLength_;
  if (n > txLength_ - txSent_) n = (uint8_t)(txLength_ - txSent_);
  hal::write(tx_.frame() + txSent_, n);
  txSent_ = (uint8_t)(txSent_ + n);
  if (txSent_ >= txLength_) txLength_ = 0;
}

void MAXL_Device::flushTransmit() {
  if (!txLength_) return;
  hal::write(tx_.frame() + txSent_, (uint8_t)(txLength_ - txSent_));
  txLength_ = 0;
}
