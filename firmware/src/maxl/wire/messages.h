// Payload layouts of every message in docs/protocol.md §4, both directions.
//
// Fixed-size messages are plain structs with parse() (exact length, or
// MALFORMED) and write(). Messages that carry lists (GEOMETRY, TIMING, EVENTS,
// SAMPLES) are read through "views": parse() checks the whole payload's
// structure first, so a handler can refuse a malformed frame before it changes
// anything, then the entries are read one by one straight from the payload
// bytes (no copy, no big struct on a 2 KB device's stack).
//
// These checks are structural only (lengths, varints, shape bits, name
// lengths). Whether the values make sense (a positive length, a known
// segment...) is the device's business, see device/handlers.
#ifndef MAXL_WIRE_MESSAGES_H
#define MAXL_WIRE_MESSAGES_H

#include <stdint.h>

#include "maxl/wire/bytes.h"
#include "maxl/wire/protocol.h"

namespace maxl_fw {
namespace msg {

// ---------------------------------------------------------------- author to device

struct HelloRequest {
  uint8_t protocol;
};
struct Ping {
  uint16_t pingId;
  uint16_t replyAfter;  // µs the PONG waits after the ping arrived (clock sync dither, protocol §4)
};
struct Clock {
  uint32_t deviceRef;
  uint32_t authorRef;
  int32_t ratePpb;
};
struct Subscribe {
  uint8_t reader;
  uint8_t kind;
  uint8_t slot;
};
struct ReplaceTail {
  uint16_t fromId;
};
struct Halt {
  uint8_t mode;
  uint32_t at;
};

bool parse(const uint8_t* p, uint8_t n, HelloRequest& m);
bool parse(const uint8_t* p, uint8_t n, Ping& m);
bool parse(const uint8_t* p, uint8_t n, Clock& m);
bool parse(const uint8_t* p, uint8_t n, Subscribe& m);
bool parse(const uint8_t* p, uint8_t n, ReplaceTail& m);
bool parse(const uint8_t* p, uint8_t n, Halt& m);
void write(ByteWriter& w, const HelloRequest& m);
void write(ByteWriter& w, const Ping& m);
void write(ByteWriter& w, const Clock& m);
void write(ByteWriter& w, const Subscribe& m);
void write(ByteWriter& w, const ReplaceTail& m);
void write(ByteWriter& w, const Halt& m);

// GEOMETRY: firstId:u16 count:u8 flags:u8 [p0:i32 × P] count × (length:f32 p1:i32 × P)
// Fixed-size entries, so they are read by index.
class GeometryView {
 public:
  bool parse(const uint8_t* p, uint8_t n, uint8_t positionSlots);
  uint16_t firstId;
  uint8_t count;
  uint8_t flags;
  bool hasP0() const { return flags & GEOMETRY_HAS_P0; }
  int32_t p0(uint8_t slot) const;
  float length(uint8_t k) const;
  int32_t p1(uint8_t k, uint8_t slot) const;

 private:
  const uint8_t* p_;
  uint8_t slots_;
  uint8_t segmentsAt_;
};
// p0 may be null when flags lacks HAS_P0; p1 holds count × P values, segment-major.
void writeGeometry(ByteWriter& w, uint16_t firstId, uint8_t count, uint8_t flags, uint8_t positionSlots,
                   const int32_t* p0, const float* lengths, const int32_t* p1);

// TIMING: firstId:u16 count:u8 flags:u8 stopDecel:f32 [start:u32]
//         count × (shape:u8 durations:varint × phases(shape) alpha:f32)
struct TimingSegment {
  uint8_t shape;
  uint8_t phaseCount;
  uint32_t durations[3];  // µs, phaseCount of them
  float alpha;            // 1/s²
  // Phase k's kind (phase::ACCELERATE...), k < phaseCount.
  uint8_t phaseKind(uint8_t k) const { return (uint8_t)((shape >> (2 * k)) & 3); }
};
// Number of phases in `shape` (1..3), or -1 if its bits are not a valid
// list: no phase at all, a phase after a NONE, or bits 6–7 set.
int8_t shapePhaseCount(uint8_t shape);

class TimingView {
 public:
  bool parse(const uint8_t* p, uint8_t n);
  uint16_t firstId;
  uint8_t count;
  uint8_t flags;
  float stopDecel;
  uint32_t start;  // valid when hasStart()
  bool hasStart() const { return flags & TIMING_HAS_START; }
  // Entries in order; call rewind() to read them again.
  void rewind();
  bool next(TimingSegment& s);

 private:
  const uint8_t* p_;
  uint8_t n_;
  uint8_t entriesAt_;
  uint8_t pos_;
};
void writeTiming(ByteWriter& w, uint16_t firstId, uint8_t count, uint8_t flags, float stopDecel, uint32_t start,
                 const TimingSegment* segments);

// EVENTS: segmentId:u16 slot:u8 firstIndex:u16 count:u8 count × (offset:varint value:f32)
struct EventEntry {
  uint32_t offset;  // µs after the segment's start
  float value;
};
class EventsView {
 public:
  bool parse(const uint8_t* p, uint8_t n);
  uint16_t segmentId;
  uint8_t slot;
  uint16_t firstIndex;
  uint8_t count;
  void rewind();
  bool next(EventEntry& e);

 private:
  const uint8_t* p_;
  uint8_t n_;
  uint8_t pos_;
};
void writeEvents(ByteWriter& w, uint16_t segmentId, uint8_t slot, uint16_t firstIndex, uint8_t count,
                 const EventEntry* entries);

// ---------------------------------------------------------------- device to author

struct Name {
  const char* text;  // not NUL-terminated when parsed from a payload
  uint8_t length;
};
struct Hello {
  uint8_t protocol;
  uint8_t fwMajor, fwMinor, fwPatch;
  uint32_t clockHz;
  uint8_t segmentCapacity;
  uint8_t eventCapacity;
  uint8_t readerCount;
  Name name;
};
struct Reader {
  uint8_t index;
  uint8_t kind;
  uint8_t channels;
  Name name;
};
struct Ack {
  uint8_t ackSeq;
  uint8_t freeSegments;
  uint8_t freeEvents;
};
struct Nack {
  uint8_t seq;
  uint8_t reason;
  uint16_t detail;
};
struct Pong {
  uint16_t pingId;
  uint32_t rxTime;
  uint32_t txTime;
};
struct Status {
  uint32_t now;
  uint8_t state;
  uint16_t segmentId;
  float sigma;
  uint8_t depth;
  uint8_t flags;
};

bool parse(const uint8_t* p, uint8_t n, Hello& m);
bool parse(const uint8_t* p, uint8_t n, Reader& m);
bool parse(const uint8_t* p, uint8_t n, Ack& m);
bool parse(const uint8_t* p, uint8_t n, Nack& m);
bool parse(const uint8_t* p, uint8_t n, Pong& m);
bool parse(const uint8_t* p, uint8_t n, Status& m);
void write(ByteWriter& w, const Hello& m);
void write(ByteWriter& w, const Reader& m);
void write(ByteWriter& w, const Ack& m);
void write(ByteWriter& w, const Nack& m);
void write(ByteWriter& w, const Pong& m);
void write(ByteWriter& w, const Status& m);

// SAMPLES: reader:u8 sampleSeq:u16 count:u8 t0:u32 count × (dt:varint value:f32 × channels)
// The channel count is not on the wire: it is the reader's (READER.channels).
const uint8_t SAMPLES_HEADER = 8;
class SamplesView {
 public:
  bool parse(const uint8_t* p, uint8_t n, uint8_t channels);
  uint8_t reader;
  uint16_t sampleSeq;
  uint8_t count;
  uint32_t t0;
  void rewind();
  // Reads one sample: its dt, and `channels` values into `values`.
  bool next(uint32_t& dt, float* values);

 private:
  const uint8_t* p_;
  uint8_t n_;
  uint8_t channels_;
  uint8_t pos_;
};
void writeSamplesHeader(ByteWriter& w, uint8_t reader, uint16_t sampleSeq, uint8_t count, uint32_t t0);

// ---------------------------------------------------------------- any message

// What a parser needs that is not in the payload.
struct DecodeContext {
  uint8_t positionSlots;   // P, for GEOMETRY
  uint8_t sampleChannels;  // for SAMPLES
};
// Structural check of any payload: CODEC_OK, CODEC_MALFORMED or
// CODEC_UNKNOWN_MESSAGE (a type the spec does not define).
CodecError checkPayload(uint8_t type, const uint8_t* p, uint8_t n, const DecodeContext& context);

}  // namespace msg
}  // namespace maxl_fw

#endif
