// MAXL_Device: one handler per author-to-device message (protocol §4).
// Each returns the frame's answer: ack, or a nack reason and detail. A handler
// checks everything before it changes anything, so a refused frame leaves the
// device as it was (LATE_SEGMENT keeps the segments before the late one, as
// the spec says).
#include <math.h>

#include "maxl/device/device.h"
#include "maxl/motion/profile.h"
#include "maxl/readers/reader.h"
#include "maxl/time/wrap.h"
#include "maxl/wire/messages.h"

using namespace maxl_fw;

MAXL_Device::Answer MAXL_Device::handle(uint8_t t, const uint8_t* p, uint8_t n) {
  switch (t) {
    case type::PING_REQUEST: return onPing(p, n);
    case type::CLOCK: return onClock(p, n);
    case type::SUBSCRIBE: return onSubscribe(p, n);
    case type::GEOMETRY: return onGeometry(p, n);
    case type::TIMING: return onTiming(p, n);
    case type::EVENTS: return onEvents(p, n);
    case type::REPLACE_TAIL: return onReplaceTail(p, n);
    case type::HALT: return onHalt(p, n);
    case type::STATUS_REQUEST:
      if (n != 0) return nack(nack::MALFORMED, t);
      sendStatus();
      return ack();
    case type::HELLO_REQUEST:  // only a malformed one gets here
      return nack(nack::MALFORMED, t);
    default:
      return nack(nack::UNKNOWN_MESSAGE, t);
  }
}

// The PONG goes out replyAfter µs after the ping arrived (at once, before the
// ACK, when 0). The author draws replyAfter at random: on a link that moves data
// in fixed slots (USB frames), a reply sent at a fixed phase after a slot-aligned
// arrival would always wait the same time for the next slot, and clock sync could
// never see the return trip at its fastest. txTime says when it really went.
MAXL_Device::Answer MAXL_Device::onPing(const uint8_t* p, uint8_t n) {
  msg::Ping m;
  if (!msg::parse(p, n, m)) return nack(nack::MALFORMED, type::PING_REQUEST);
  if (pongPending_) sendPong(false);  // one waits at a time: the older one goes now
  pongId_ = m.pingId;
  pongReceivedAt_ = rx_.arrivedAt();
  pongDueAt_ = pongReceivedAt_ + m.replyAfter;
  pongPending_ = true;
  if (m.replyAfter == 0) sendPong(false);
  return ack();
}

MAXL_Device::Answer MAXL_Device::onClock(const uint8_t* p, uint8_t n) {
  msg::Clock m;
  if (!msg::parse(p, n, m)) return nack(nack::MALFORMED, type::CLOCK);
  clock_.set(m.deviceRef, m.authorRef, m.ratePpb);
  return ack();
}

MAXL_Device::Answer MAXL_Device::onSubscribe(const uint8_t* p, uint8_t n) {
  msg::Subscribe m;
  if (!msg::parse(p, n, m)) return nack(nack::MALFORMED, type::SUBSCRIBE);
  MAXL_Reader* r = MAXL_Reader::at(m.reader);
  if (!r || r->kind() != m.kind) return nack(nack::BAD_SUBSCRIPTION, m.reader);
  uint8_t slots = m.kind == kind::POSITION ? MAXL_POSITION_SLOTS : m.kind == kind::EVENT ? MAXL_EVENT_SLOTS : 1;
  if (m.slot >= slots) return nack(nack::BAD_SUBSCRIPTION, m.reader);
  if (motion_.queue().count() > 0) return nack(nack::BAD_SUBSCRIPTION, m.reader);
  r->bind(m.slot);
  // P: one more than the highest position slot subscribed.
  uint8_t active = 0;
  for (MAXL_Reader* q = MAXL_Reader::first(); q; q = q->next())
    if (q->subscribed() && q->kind() == kind::POSITION && q->slot() + 1 > active) active = (uint8_t)(q->slot() + 1);
  motion_.setActiveSlots(active);
  return ack();
}

MAXL_Device::Answer MAXL_Device::onGeometry(const uint8_t* p, uint8_t n) {
  const uint8_t P = motion_.activeSlots();
  msg::GeometryView g;
  if (!g.parse(p, n, P) || g.count == 0) return nack(nack::MALFORMED, type::GEOMETRY);
  SegmentQueue& q = motion_.queue();
  bool empty = q.count() == 0;
  // On an empty queue a p0 (re)starts the queue at any id; otherwise ids
  // continue and each segment starts where the one before it ended.
  bool restart = empty && g.hasP0();
  if (!restart) {
    if (empty && motion_.knownSlots() < P) return nack(nack::MALFORMED, type::GEOMETRY);  // where from?
    if (g.firstId != q.nextId()) return nack(nack::MALFORMED, q.nextId());
  }
  // Lengths are >= 0 and finite. A length of 0 is a dwell, which holds its
  // start: its p1 must be where it starts (the p1 before it, or p0).
  for (uint8_t k = 0; k < g.count; k++) {
    float length = g.length(k);
    if (!(length >= 0.0f) || !isFiniteFloat(length)) return nack(nack::MALFORMED, type::GEOMETRY);
    if (length == 0.0f) {
      for (uint8_t i = 0; i < P; i++) {
        int32_t from = k > 0 ? g.p1((uint8_t)(k - 1), i) : restart ? g.p0(i) : motion_.startOf(q.count(), i);
        if (g.p1(k, i) != from) return nack(nack::MALFORMED, type::GEOMETRY);
      }
    }
  }
  if (q.free() < g.count) {
    flags_ |= status_flag::QUEUE_FULL;
    return nack(nack::QUEUE_FULL, q.free());
  }
  if (restart) {
    int32_t p0[MAXL_POSITION_SLOTS];
    for (uint8_t i = 0; i < P; i++) p0[i] = g.p0(i);
    q.clear(g.firstId);
    motion_.setBase(p0, P);
    for (uint8_t i = 0; i < MAXL_EVENT_SLOTS; i++) eventTracks_[i].active = false;
  }
  for (uint8_t k = 0; k < g.count; k++) {
    Segment& s = q.append();
    s.length = g.length(k);
    for (uint8_t i = 0; i < MAXL_POSITION_SLOTS; i++) s.p1[i] = i < P ? g.p1(k, i) : 0;
  }
  return ack();
}

MAXL_Device::Answer MAXL_Device::onTiming(const uint8_t* p, uint8_t n) {
  msg::TimingView t;
  if (!t.parse(p, n) || t.count == 0) return nack(nack::MALFORMED, type::TIMING);
  if (!(t.stopDecel > 0.0f) || !isFiniteFloat(t.stopDecel)) return nack(nack::MALFORMED, type::TIMING);
#if MAXL_CLOCK_JUMP_US
  if (flags_ & status_flag::CLOCK_JUMP) return nack(nack::CLOCK_JUMP, t.firstId);  // until a new session
#endif
  SegmentQueue& q = motion_.queue();
  const uint8_t first = q.timed();
  // Timing goes to the first segments without it, and only to queued ones.
  if (t.firstId != (uint16_t)(q.headId() + first)) return nack(nack::UNKNOWN_SEGMENT, t.firstId);
  if ((uint16_t)first + t.count > q.count()) return nack(nack::UNKNOWN_SEGMENT, q.nextId());
  uint32_t start = t.start;
  if (first > 0) {
    // After the timed segments queued: contiguous with them, or not overlapping.
    uint32_t previousEnd = q.at((uint8_t)(first - 1)).end();
    if (!t.hasStart()) start = previousEnd;
    if (timeBefore(start, previousEnd)) return nack(nack::MALFORMED, type::TIMING);  // overlaps
  } else if (!t.hasStart() || motion_.headStarted()) {
    // No timed segment left to continue. Without timing in the session (or
    // since HALT 0) there is nothing to continue; otherwise that timing is over
    // (run, braked along, or dropped), so the start would be in the past. And
    // the device braking along (or stopped inside) that segment: too late too.
    if (!motion_.timingGiven()) return nack(nack::MALFORMED, type::TIMING);  // contiguous with nothing
    flags_ |= status_flag::LATE;
    return nack(nack::LATE_SEGMENT, t.firstId);
  }
  // Write the timing into the (still provisional) segments; it only counts
  // once markTimed() says so, so a refusal half-way leaves nothing applied.
  const uint8_t P = motion_.activeSlots();
  int16_t late = -1;
  for (uint8_t k = 0; k < t.count; k++) {
    msg::TimingSegment ts;
    t.next(ts);
    uint8_t index = (uint8_t)(first + k);
    Segment& s = q.at(index);
    s.shape = ts.shape;
    s.phaseCount = ts.phaseCount;
    for (uint8_t i = 0; i < 3; i++) s.durations[i] = ts.durations[i];
    s.alpha = ts.alpha;
    float nuPeak, nuEnd;
    if (!solveProfile(s, nuPeak, nuEnd)) return nack(nack::MALFORMED, type::TIMING);
    for (uint8_t i = 0; i < P; i++) {
      float delta = (float)((int64_t)s.p1[i] - (int64_t)motion_.startOf(index, i));
      if (!slotCoefficients(delta, s.nu0, nuPeak, s.alpha, s.b0[i], s.cmag[i]))
        return nack(nack::MALFORMED, type::TIMING);
    }
    s.start = start;
    if (late < 0 && timeBefore(start, now_)) late = k;
    start += s.duration();
  }
  if (late != 0) {
    motion_.setStopDecel(t.stopDecel);
    motion_.timingAdded();
  }
  if (late >= 0) {
    motion_.markTimed((uint8_t)(first + late));
    flags_ |= status_flag::LATE;
    return nack(nack::LATE_SEGMENT, (uint16_t)(t.firstId + late));
  }
  motion_.markTimed((uint8_t)(first + t.count));
  return ack();
}

MAXL_Device::Answer MAXL_Device::onEvents(const uint8_t* p, uint8_t n) {
  msg::EventsView e;
  if (!e.parse(p, n) || e.count == 0 || e.slot >= MAXL_EVENT_SLOTS) return nack(nack::MALFORMED, type::EVENTS);
  SegmentQueue& q = motion_.queue();
  int16_t index = q.find(e.segmentId);
  if (index < 0 || index >= q.timed()) return nack(nack::UNKNOWN_SEGMENT, e.segmentId);
  const Segment& s = q.at((uint8_t)index);
  EventTrack& track = eventTracks_[e.slot];
  // Continuation: firstIndex must be the count already received for this
  // segment and slot; a slot's segments come in order.
  uint32_t lastOffset = 0;
  if (track.active && track.segmentId == e.segmentId) {
    if (e.firstIndex != track.next) return nack(nack::MALFORMED, type::EVENTS);
    lastOffset = track.lastOffset;
  } else {
    if (e.firstIndex != 0) return nack(nack::MALFORMED, type::EVENTS);
    if (track.active && (int16_t)(e.segmentId - track.segmentId) < 0) return nack(nack::MALFORMED, type::EVENTS);
  }
  const uint32_t duration = s.duration();
  msg::EventEntry entry;
  for (uint8_t k = 0; k < e.count; k++) {
    e.next(entry);
    if (entry.offset < lastOffset || entry.offset > duration) return nack(nack::MALFORMED, type::EVENTS);
    lastOffset = entry.offset;
  }
  if (events_.free() < e.count) {
    flags_ |= status_flag::EVENT_OVERFLOW;
    return nack(nack::QUEUE_FULL, events_.free());
  }
  e.rewind();
  for (uint8_t k = 0; k < e.count; k++) {
    e.next(entry);
    events_.push(s.start + entry.offset, entry.value, e.segmentId, e.slot);
  }
  track.active = true;
  track.segmentId = e.segmentId;
  track.next = (uint16_t)(e.firstIndex + e.count);
  track.lastOffset = lastOffset;
  return ack();
}

MAXL_Device::Answer MAXL_Device::onReplaceTail(const uint8_t* p, uint8_t n) {
  msg::ReplaceTail m;
  if (!msg::parse(p, n, m)) return nack(nack::MALFORMED, type::REPLACE_TAIL);
  SegmentQueue& q = motion_.queue();
  int16_t index = q.find(m.fromId);
  if (index < 0) {
    if (m.fromId == q.nextId()) return ack();  // nothing after the last one
    if ((int16_t)(m.fromId - q.headId()) < 0) return nack(nack::ALREADY_STARTED, m.fromId);  // already run
    return nack(nack::UNKNOWN_SEGMENT, m.fromId);
  }
  if (index == 0 && motion_.headStarted()) return nack(nack::ALREADY_STARTED, m.fromId);
  motion_.dropFrom((uint8_t)index);
  events_.dropFromSegment(m.fromId);
  forgetEventTracksFrom(m.fromId);
  return ack();
}

MAXL_Device::Answer MAXL_Device::onHalt(const uint8_t* p, uint8_t n) {
  msg::Halt m;
  if (!msg::parse(p, n, m)) return nack(nack::MALFORMED, type::HALT);
  if (m.mode == HALT_NOW) {
    motion_.haltNow(now_);
    events_.clear();
    for (uint8_t i = 0; i < MAXL_EVENT_SLOTS; i++) eventTracks_[i].active = false;
    return ack();
  }
#if MAXL_HALT_BRAKE
  if (m.mode != HALT_BRAKE_AT) return nack(nack::MALFORMED, type::HALT);
  bool onTime = motion_.haltBrakeAt(now_, m.at);
  if (!onTime) flags_ |= status_flag::LATE;
  // Changes timed after the brake start went with their timing.
  events_.dropAfter(onTime ? m.at : now_);
  const SegmentQueue& q = motion_.queue();
  forgetEventTracksFrom((uint16_t)(q.headId() + q.timed()));
  return ack();
#else
  return nack(nack::MALFORMED, type::HALT);  // built without HALT mode 1 (config.h)
#endif
}

void MAXL_Device::forgetEventTracksFrom(uint16_t segmentId) {
  for (uint8_t i = 0; i < MAXL_EVENT_SLOTS; i++) {
    EventTrack& t = eventTracks_[i];
    if (t.active && (int16_t)(t.segmentId - segmentId) >= 0) t.active = false;
  }
}
