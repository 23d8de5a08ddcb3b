#include "maxl/wire/messages.h"

namespace maxl_fw {
namespace msg {

namespace {
int32_t readI32(const uint8_t* p) {
  return (int32_t)((uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24));
}
float readF32(const uint8_t* p) {
  ByteReader r(p, 4);
  return r.f32();
}
}  // namespace

// ------------------------------------------------------------ fixed messages

bool parse(const uint8_t* p, uint8_t n, HelloRequest& m) {
  ByteReader r(p, n);
  m.protocol = r.u8();
  return r.atEnd();
}
bool parse(const uint8_t* p, uint8_t n, Ping& m) {
  ByteReader r(p, n);
  m.pingId = r.u16();
  m.replyAfter = r.u16();
  return r.atEnd();
}
bool parse(const uint8_t* p, uint8_t n, Clock& m) {
  ByteReader r(p, n);
  m.deviceRef = r.u32();
  m.authorRef = r.u32();
  m.ratePpb = r.i32();
  return r.atEnd();
}
bool parse(const uint8_t* p, uint8_t n, Subscribe& m) {
  ByteReader r(p, n);
  m.reader = r.u8();
  m.kind = r.u8();
  m.slot = r.u8();
  return r.atEnd();
}
bool parse(const uint8_t* p, uint8_t n, ReplaceTail& m) {
  ByteReader r(p, n);
  m.fromId = r.u16();
  return r.atEnd();
}
bool parse(const uint8_t* p, uint8_t n, Halt& m) {
  ByteReader r(p, n);
  m.mode = r.u8();
  m.at = r.u32();
  return r.atEnd();
}
void write(ByteWriter& w, const HelloRequest& m) { w.u8(m.protocol); }
void write(ByteWriter& w, const Ping& m) {
  w.u16(m.pingId);
  w.u16(m.replyAfter);
}
void write(ByteWriter& w, const Clock& m) {
  w.u32(m.deviceRef);
  w.u32(m.authorRef);
  w.i32(m.ratePpb);
}
void write(ByteWriter& w, const Subscribe& m) {
  w.u8(m.reader);
  w.u8(m.kind);
  w.u8(m.slot);
}
void write(ByteWriter& w, const ReplaceTail& m) { w.u16(m.fromId); }
void write(ByteWriter& w, const Halt& m) {
  w.u8(m.mode);
  w.u32(m.at);
}

bool parse(const uint8_t* p, uint8_t n, Hello& m) {
  ByteReader r(p, n);
  m.protocol = r.u8();
  m.fwMajor = r.u8();
  m.fwMinor = r.u8();
  m.fwPatch = r.u8();
  m.clockHz = r.u32();
  m.segmentCapacity = r.u8();
  m.eventCapacity = r.u8();
  m.readerCount = r.u8();
  m.name.text = r.str(m.name.length, MAX_NAME);
  return r.atEnd();
}
bool parse(const uint8_t* p, uint8_t n, Reader& m) {
  ByteReader r(p, n);
  m.index = r.u8();
  m.kind = r.u8();
  m.channels = r.u8();
  m.name.text = r.str(m.name.length, MAX_NAME);
  return r.atEnd();
}
bool parse(const uint8_t* p, uint8_t n, Ack& m) {
  ByteReader r(p, n);
  m.ackSeq = r.u8();
  m.freeSegments = r.u8();
  m.freeEvents = r.u8();
  return r.atEnd();
}
bool parse(const uint8_t* p, uint8_t n, Nack& m) {
  ByteReader r(p, n);
  m.seq = r.u8();
  m.reason = r.u8();
  m.detail = r.u16();
  return r.atEnd();
}
bool parse(const uint8_t* p, uint8_t n, Pong& m) {
  ByteReader r(p, n);
  m.pingId = r.u16();
  m.rxTime = r.u32();
  m.txTime = r.u32();
  return r.atEnd();
}
bool parse(const uint8_t* p, uint8_t n, Status& m) {
  ByteReader r(p, n);
  m.now = r.u32();
  m.state = r.u8();
  m.segmentId = r.u16();
  m.sigma = r.f32();
  m.depth = r.u8();
  m.flags = r.u8();
  return r.atEnd();
}
void write(ByteWriter& w, const Hello& m) {
  w.u8(m.protocol);
  w.u8(m.fwMajor);
  w.u8(m.fwMinor);
  w.u8(m.fwPatch);
  w.u32(m.clockHz);
  w.u8(m.segmentCapacity);
  w.u8(m.eventCapacity);
  w.u8(m.readerCount);
  w.str(m.name.text, m.name.length);
}
void write(ByteWriter& w, const Reader& m) {
  w.u8(m.index);
  w.u8(m.kind);
  w.u8(m.channels);
  w.str(m.name.text, m.name.length);
}
void write(ByteWriter& w, const Ack& m) {
  w.u8(m.ackSeq);
  w.u8(m.freeSegments);
  w.u8(m.freeEvents);
}
void write(ByteWriter& w, const Nack& m) {
  w.u8(m.seq);
  w.u8(m.reason);
  w.u16(m.detail);
}
void write(ByteWriter& w, const Pong& m) {
  w.u16(m.pingId);
  w.u32(m.rxTime);
  w.u32(m.txTime);
}
void write(ByteWriter& w, const Status& m) {
  w.u32(m.now);
  w.u8(m.state);
  w.u16(m.segmentId);
  w.f32(m.sigma);
  w.u8(m.depth);
  w.u8(m.flags);
}

// ------------------------------------------------------------ GEOMETRY

bool GeometryView::parse(const uint8_t* p, uint8_t n, uint8_t positionSlots) {
  ByteReader r(p, n);
  firstId = r.u16();
  count = r.u8();
  flags = r.u8();
  if (r.failed()) return false;
  p_ = p;
  slots_ = positionSlots;
  uint16_t perSegment = (uint16_t)(4 + 4 * (uint16_t)positionSlots);
  uint16_t expected = (uint16_t)(4 + (hasP0() ? 4 * (uint16_t)positionSlots : 0) + (uint32_t)count * perSegment);
  segmentsAt_ = (uint8_t)(4 + (hasP0() ? 4 * positionSlots : 0));
  return expected == n;
}
int32_t GeometryView::p0(uint8_t slot) const { return readI32(p_ + 4 + 4 * slot); }
float GeometryView::length(uint8_t k) const { return readF32(p_ + segmentsAt_ + k * (4 + 4 * slots_)); }
int32_t GeometryView::p1(uint8_t k, uint8_t slot) const {
  return readI32(p_ + segmentsAt_ + k * (4 + 4 * slots_) + 4 + 4 * slot);
}
void writeGeometry(ByteWriter& w, uint16_t firstId, uint8_t count, uint8_t flags, uint8_t positionSlots,
                   const int32_t* p0, const float* lengths, const int32_t* p1) {
  w.u16(firstId);
  w.u8(count);
  w.u8(flags);
  if (flags & GEOMETRY_HAS_P0)
    for (uint8_t i = 0; i < positionSlots; i++) w.i32(p0[i]);
  for (uint8_t k = 0; k < count; k++) {
    w.f32(lengths[k]);
    for (uint8_t i = 0; i < positionSlots; i++) w.i32(p1[k * positionSlots + i]);
  }
}

// ------------------------------------------------------------ TIMING

int8_t shapePhaseCount(uint8_t shape) {
  if (shape & 0xC0) return -1;
  int8_t n = 0;
  while (n < 3 && ((shape >> (2 * n)) & 3) != phase::NONE) n++;
  if (n == 0) return -1;            // no phase at all
  if (shape >> (2 * n)) return -1;  // a phase after NONE
  return n;
}

namespace {
bool readTimingSegment(ByteReader& r, TimingSegment& s) {
  s.shape = r.u8();
  if (r.failed()) return false;
  int8_t phases = shapePhaseCount(s.shape);
  if (phases < 0) return false;
  s.phaseCount = (uint8_t)phases;
  for (uint8_t k = 0; k < 3; k++) s.durations[k] = k < s.phaseCount ? r.varint() : 0;
  s.alpha = r.f32();
  return !r.failed();
}
}  // namespace

bool TimingView::parse(const uint8_t* p, uint8_t n) {
  ByteReader r(p, n);
  firstId = r.u16();
  count = r.u8();
  flags = r.u8();
  stopDecel = r.f32();
  start = hasStart() ? r.u32() : 0;
  if (r.failed()) return false;
  p_ = p;
  n_ = n;
  entriesAt_ = r.position();
  TimingSegment s;
  for (uint8_t k = 0; k < count; k++)
    if (!readTimingSegment(r, s)) return false;
  if (!r.atEnd()) return false;
  rewind();
  return true;
}
void TimingView::rewind() { pos_ = entriesAt_; }
bool TimingView::next(TimingSegment& s) {
  ByteReader r(p_ + pos_, (uint8_t)(n_ - pos_));
  bool ok = readTimingSegment(r, s);
  pos_ = (uint8_t)(pos_ + r.position());
  return ok;
}
void writeTiming(ByteWriter& w, uint16_t firstId, uint8_t count, uint8_t flags, float stopDecel, uint32_t start,
                 const TimingSegment* segments) {
  w.u16(firstId);
  w.u8(count);
  w.u8(flags);
  w.f32(stopDecel);
  if (flags & TIMING_HAS_START) w.u32(start);
  for (uint8_t k = 0; k < count; k++) {
    const TimingSegment& s = segments[k];
    w.u8(s.shape);
    int8_t phases = shapePhaseCount(s.shape);
    for (int8_t i = 0; i < phases; i++) w.varint(s.durations[i]);
    w.f32(s.alpha);
  }
}

// ------------------------------------------------------------ EVENTS

bool EventsView::parse(const uint8_t* p, uint8_t n) {
  ByteReader r(p, n);
  segmentId = r.u16();
  slot = r.u8();
  firstIndex = r.u16();
  count = r.u8();
  if (r.failed()) return false;
  p_ = p;
  n_ = n;
  for (uint8_t k = 0; k < count; k++) {
    r.varint();
    r.f32();
  }
  if (!r.atEnd()) return false;
  rewind();
  return true;
}
void EventsView::rewind() { pos_ = 6; }
bool EventsView::next(EventEntry& e) {
  ByteReader r(p_ + pos_, (uint8_t)(n_ - pos_));
  e.offset = r.varint();
  e.value = r.f32();
  pos_ = (uint8_t)(pos_ + r.position());
  return !r.failed();
}
void writeEvents(ByteWriter& w, uint16_t segmentId, uint8_t slot, uint16_t firstIndex, uint8_t count,
                 const EventEntry* entries) {
  w.u16(segmentId);
  w.u8(slot);
  w.u16(firstIndex);
  w.u8(count);
  for (uint8_t k = 0; k < count; k++) {
    w.varint(entries[k].offset);
    w.f32(entries[k].value);
  }
}

// ------------------------------------------------------------ SAMPLES

bool SamplesView::parse(const uint8_t* p, uint8_t n, uint8_t channels) {
  ByteReader r(p, n);
  reader = r.u8();
  sampleSeq = r.u16();
  count = r.u8();
  t0 = r.u32();
  if (r.failed()) return false;
  p_ = p;
  n_ = n;
  channels_ = channels;
  for (uint8_t k = 0; k < count; k++) {
    r.varint();
    for (uint8_t c = 0; c < channels; c++) r.f32();
  }
  if (!r.atEnd()) return false;
  rewind();
  return true;
}
void SamplesView::rewind() { pos_ = SAMPLES_HEADER; }
bool SamplesView::next(uint32_t& dt, float* values) {
  ByteReader r(p_ + pos_, (uint8_t)(n_ - pos_));
  dt = r.varint();
  for (uint8_t c = 0; c < channels_; c++) values[c] = r.f32();
  pos_ = (uint8_t)(pos_ + r.position());
  return !r.failed();
}
void writeSamplesHeader(ByteWriter& w, uint8_t reader, uint16_t sampleSeq, uint8_t count, uint32_t t0) {
  w.u8(reader);
  w.u16(sampleSeq);
  w.u8(count);
  w.u32(t0);
}

// ------------------------------------------------------------ any message

CodecError checkPayload(uint8_t t, const uint8_t* p, uint8_t n, const DecodeContext& context) {
  bool ok;
  switch (t) {
    case type::HELLO_REQUEST: { HelloRequest m; ok = parse(p, n, m); break; }
    case type::PING_REQUEST: { Ping m; ok = parse(p, n, m); break; }
    case type::CLOCK: { Clock m; ok = parse(p, n, m); break; }
    case type::SUBSCRIBE: { Subscribe m; ok = parse(p, n, m); break; }
    case type::GEOMETRY: { GeometryView v; ok = v.parse(p, n, context.positionSlots); break; }
    case type::TIMING: { TimingView v; ok = v.parse(p, n); break; }
    case type::EVENTS: { EventsView v; ok = v.parse(p, n); break; }
    case type::REPLACE_TAIL: { ReplaceTail m; ok = parse(p, n, m); break; }
    case type::HALT: { Halt m; ok = parse(p, n, m); break; }
    case type::STATUS_REQUEST: ok = n == 0; break;
    case type::HELLO: { Hello m; ok = parse(p, n, m); break; }
    case type::READER: { Reader m; ok = parse(p, n, m); break; }
    case type::ACK: { Ack m; ok = parse(p, n, m); break; }
    case type::NACK: { Nack m; ok = parse(p, n, m); break; }
    case type::PONG: { Pong m; ok = parse(p, n, m); break; }
    case type::STATUS: { Status m; ok = parse(p, n, m); break; }
    case type::SAMPLES: { SamplesView v; ok = v.parse(p, n, context.sampleChannels); break; }
    default: return CODEC_UNKNOWN_MESSAGE;
  }
  return ok ? CODEC_OK : CODEC_MALFORMED;
}

}  // namespace msg
}  // namespace maxl_fw
