// The device's segment queue: a ring of MAXL_SEGMENT_CAPACITY segments with
// consecutive ids. The first `timed` segments have timing; the rest are
// provisional geometry (protocol §1, §6). Timing is only ever given to the
// first segment without it, so the timed ones always form a prefix.
#ifndef MAXL_MOTION_SEGMENT_QUEUE_H
#define MAXL_MOTION_SEGMENT_QUEUE_H

#include <stdint.h>

#include "maxl/config.h"
#include "maxl/motion/segment.h"

namespace maxl_fw {

class SegmentQueue {
 public:
  SegmentQueue() { clear(0); }

  // Empties the queue; the next segment appended gets id `nextId`.
  void clear(uint16_t nextId) {
    head_ = 0;
    count_ = 0;
    timed_ = 0;
    headId_ = nextId;
  }

  uint8_t count() const { return count_; }
  uint8_t timed() const { return timed_; }
  uint8_t provisional() const { return (uint8_t)(count_ - timed_); }
  uint8_t free() const { return (uint8_t)(MAXL_SEGMENT_CAPACITY - count_); }
  uint16_t headId() const { return headId_; }
  uint16_t nextId() const { return (uint16_t)(headId_ + count_); }

  // Segment at position i from the head (0 = head), i < count().
  Segment& at(uint8_t i) { return ring_[index(i)]; }
  const Segment& at(uint8_t i) const { return ring_[index(i)]; }
  Segment& head() { return ring_[head_]; }

  // Position of segment `id` from the head, or -1 if it is not queued.
  int16_t find(uint16_t id) const {
    uint16_t i = (uint16_t)(id - headId_);
    return i < count_ ? (int16_t)i : -1;
  }

  // Appends a segment (geometry only) and returns it; the caller checked free().
  Segment& append() {
    Segment& s = ring_[index(count_)];
    count_++;
    return s;
  }
  void markTimed(uint8_t n) { timed_ = n; }

  // Drops the head (it has been run).
  void popHead() {
    head_ = index(1);
    headId_++;
    count_--;
    if (timed_) timed_--;
  }
  // Keeps only the first n segments.
  void truncate(uint8_t n) {
    if (n < count_) count_ = n;
    if (timed_ > count_) timed_ = count_;
  }

 private:
  // (head + i) mod capacity, without a division (slow on AVR): both are < capacity.
  uint8_t index(uint8_t i) const {
    uint16_t j = (uint16_t)head_ + i;
    return (uint8_t)(j >= MAXL_SEGMENT_CAPACITY ? j - MAXL_SEGMENT_CAPACITY : j);
  }

  Segment ring_[MAXL_SEGMENT_CAPACITY];
  uint8_t head_;
  uint8_t count_;
  uint8_t timed_;
  uint16_t headId_;
};

}  // namespace maxl_fw

#endif
