// Event-track changes waiting for their time (protocol §4 EVENTS).
//
// One ring of MAXL_EVENT_CAPACITY entries shared by every event slot, in
// arrival order. The author sends each slot's changes in time order (segments
// in order, offsets rising), so within one slot arrival order is time order,
// but entries of different slots interleave. The next change of a slot is
// therefore its first entry in the ring; due() is one comparison with the
// earliest of those, cached in nextDue_, so the per-loop cost is tiny.
#ifndef MAXL_EVENTS_EVENT_QUEUE_H
#define MAXL_EVENTS_EVENT_QUEUE_H

#include <stdint.h>

#include "maxl/config.h"

namespace maxl_fw {

struct EventEntry {
  uint32_t time;   // device µs: segment start + offset
  float value;
  uint16_t segmentId;
  uint8_t slot;
};

class EventQueue {
 public:
  EventQueue() { clear(); }

  void clear() {
    head_ = 0;
    count_ = 0;
    pending_ = false;
  }
  uint8_t count() const { return count_; }
  uint8_t free() const { return (uint8_t)(MAXL_EVENT_CAPACITY - count_); }

  // Appends one change; the caller checked free().
  void push(uint32_t time, float value, uint16_t segmentId, uint8_t slot);

  // True when some change is due at `now` (cheap).
  bool due(uint32_t now) const;

  // Takes out the earliest due change (ties: arrival order). False if none.
  bool popDue(uint32_t now, EventEntry& out);

  // Drops every change of segment `fromId` and later (REPLACE_TAIL).
  void dropFromSegment(uint16_t fromId);
  // Drops every change after time `t` (HALT mode 1: their timing is dropped).
  void dropAfter(uint32_t t);

 private:
  uint8_t index(uint8_t i) const {
    uint16_t j = (uint16_t)head_ + i;
    return (uint8_t)(j >= MAXL_EVENT_CAPACITY ? j - MAXL_EVENT_CAPACITY : j);
  }
  void removeAt(uint8_t i);
  void refreshNextDue();

  EventEntry ring_[MAXL_EVENT_CAPACITY];
  uint8_t head_;
  uint8_t count_;
  bool pending_;
  uint32_t nextDue_;
};

}  // namespace maxl_fw

#endif
