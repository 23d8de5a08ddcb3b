// Sequence numbers of author-to-device frames (protocol §3 "Sequence numbers").
//
// A frame's seq is compared with `expected`:
//   seq == expected                      NEW: handle it, answer, expected++
//   one of the 16 before, seen this session
//                                        DUPLICATE: answer again exactly as
//                                        the first time, do not handle
//   anything else                        OUT_OF_ORDER (nack, detail = expected)
// and before the first HELLO_REQUEST there is no session at all.
//
// The answer to each of the last 16 frames is kept (48 bytes), so a resent
// frame whose nack was lost gets that nack again, not an ack.
#ifndef MAXL_SESSION_SESSION_H
#define MAXL_SESSION_SESSION_H

#include <stdint.h>

#include "maxl/wire/protocol.h"

namespace maxl_fw {

class Session {
 public:
  enum Disposition : uint8_t { NEW, DUPLICATE, OUT_OF_ORDER, NO_SESSION };

  Session() : active_(false), expected_(0), handled_(0) {}

  void end() {
    active_ = false;
    expected_ = 0;
    handled_ = 0;
  }
  // A HELLO_REQUEST (seq 0) opens a new session; record() its answer next.
  void start() {
    active_ = true;
    expected_ = 0;
    handled_ = 0;
  }
  bool active() const { return active_; }
  uint8_t expected() const { return expected_; }

  Disposition classify(uint8_t seq) const {
    if (!active_) return NO_SESSION;
    if (seq == expected_) return NEW;
    uint8_t back = (uint8_t)(expected_ - seq);
    if (back >= 1 && back <= DUPLICATE_WINDOW && back <= handled_) return DUPLICATE;
    return OUT_OF_ORDER;
  }

  // The answer to the NEW frame `expected`: reason 0 for an ack, else a nack
  // reason and its detail. Advances `expected`.
  void record(uint8_t reason, uint16_t detail) {
    Answer& a = answers_[expected_ % DUPLICATE_WINDOW];
    a.reason = reason;
    a.detail = detail;
    expected_++;
    if (handled_ < 255) handled_++;
  }
  void answerTo(uint8_t seq, uint8_t& reason, uint16_t& detail) const {
    const Answer& a = answers_[seq % DUPLICATE_WINDOW];
    reason = a.reason;
    detail = a.detail;
  }

 private:
  struct Answer {
    uint8_t reason;
    uint16_t detail;
  };
  Answer answers_[DUPLICATE_WINDOW];
  bool active_;
  uint8_t expected_;
  uint8_t handled_;
};

}  // namespace maxl_fw

#endif
