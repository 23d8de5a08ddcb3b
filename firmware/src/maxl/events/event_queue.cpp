#include "maxl/events/event_queue.h"

#include "maxl/time/wrap.h"

namespace maxl_fw {

void EventQueue::push(uint32_t time, float value, uint16_t segmentId, uint8_t slot) {
  EventEntry& e = ring_[index(count_)];
  e.time = time;
  e.value = value;
  e.segmentId = segmentId;
  e.slot = slot;
  count_++;
  refreshNextDue();
}

bool EventQueue::due(uint32_t now) const { return pending_ && timeReached(now, nextDue_); }

// The earliest of each slot's first entry. Slots are at most 32, so a bit
// mask marks the slots whose first entry has been seen.
void EventQueue::refreshNextDue() {
  pending_ = false;
  uint32_t seen = 0;
  for (uint8_t i = 0; i < count_; i++) {
    const EventEntry& e = ring_[index(i)];
    uint32_t bit = (uint32_t)1 << (e.slot & 31);
    if (seen & bit) continue;
    seen |= bit;
    if (!pending_ || timeBefore(e.time, nextDue_)) {
      nextDue_ = e.time;
      pending_ = true;
    }
  }
}

bool EventQueue::popDue(uint32_t now, EventEntry& out) {
  if (!due(now)) return false;
  // Find the slot-first entry with the earliest time (the one nextDue_ names).
  uint32_t seen = 0;
  int16_t best = -1;
  for (uint8_t i = 0; i < count_; i++) {
    const EventEntry& e = ring_[index(i)];
    uint32_t bit = (uint32_t)1 << (e.slot & 31);
    if (seen & bit) continue;
    seen |= bit;
    if (best < 0 || timeBefore(e.time, ring_[index((uint8_t)best)].time)) best = i;
  }
  out = ring_[index((uint8_t)best)];
  removeAt((uint8_t)best);
  refreshNextDue();
  return true;
}

// Removes entry i (from the head) by moving the entries before it one place
// towards the tail; usually i is 0 and nothing moves.
void EventQueue::removeAt(uint8_t i) {
  for (uint8_t k = i; k > 0; k--) ring_[index(k)] = ring_[index((uint8_t)(k - 1))];
  head_ = index(1);
  count_--;
}

void EventQueue::dropFromSegment(uint16_t fromId) {
  uint8_t kept = 0;
  for (uint8_t i = 0; i < count_; i++) {
    EventEntry e = ring_[index(i)];
    if ((int16_t)(e.segmentId - fromId) >= 0) continue;
    ring_[index(kept++)] = e;
  }
  count_ = kept;
  refreshNextDue();
}

void EventQueue::dropAfter(uint32_t t) {
  uint8_t kept = 0;
  for (uint8_t i = 0; i < count_; i++) {
    EventEntry e = ring_[index(i)];
    if (timeBefore(t, e.time)) continue;
    ring_[index(kept++)] = e;
  }
  count_ = kept;
  refreshNextDue();
}

}  // namespace maxl_fw
