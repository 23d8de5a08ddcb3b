// Runs the segment queue against the device clock: which segment and phase
// is current, every position slot's value at `now`, and the end-of-timing and
// HALT braking of protocol §6.
//
//   IDLE      at rest, no timing queued
//   WAITING   timing queued, its start still ahead (reported as running)
//   RUNNING   inside a timed segment
//   BRAKING   timing ran out while moving (or HALT mode 1): braking along the
//             provisional geometry at stopDecel
//   STOPPED   at rest after braking; needs HALT 0 and new geometry to go on
//   HALTED    after HALT mode 0
//
// The hot path, tick() while RUNNING inside one phase, is integer only (see
// fixed_point.h). Phase and segment changes are integer too. Floats are used
// when timing arrives (device handlers), when braking starts, and lazily for
// velocity/acceleration readers and STATUS.
#ifndef MAXL_MOTION_MOTION_H
#define MAXL_MOTION_MOTION_H

#include <stdint.h>

#include "maxl/config.h"
#include "maxl/motion/fixed_point.h"
#include "maxl/motion/segment_queue.h"

namespace maxl_fw {

// A read-only walk along one slot's path ahead of Motion's clock, for step
// planning (readers/step_planner.h). It follows only what is certain: the
// timed segments (up to a pending HALT's time), or the brake piece Motion is
// in. Motion's decisions (braking when the timing runs out, HALT, a new
// session) are still taken at the device clock; each one changes Motion's
// epoch(), and a lookahead with another epoch must start again from Motion.
// A lookahead evaluates with the very operations Motion uses (fixed_point.h),
// so it gives the same positions, bit for bit.
struct Lookahead {
  enum State : uint8_t { REST, RUN, BRAKE };
  uint32_t chunkStart;  // RUN/BRAKE: as Motion's
  uint32_t pieceEnd;    // RUN: end of the phase; BRAKE: end of the brake piece
  FixedTrack track;     // RUN/BRAKE: the slot's coefficients
  uint16_t segment;     // RUN: the segment followed; REST: the next one to start
  uint8_t phase;        // RUN
  uint8_t state;
  uint8_t epoch;        // Motion::epoch() when it started from Motion
};

class Motion {
 public:
  enum Mode : uint8_t { IDLE, WAITING, RUNNING, BRAKING, STOPPED, HALTED };

  Motion() : epoch_(0) { reset(); }

  // New session: empty queue, positions unknown, no timing history.
  void reset();

  // Advances to `now` (wrap-safe) and evaluates every active slot. The common
  // case, inside the current phase, is inline: one comparison, then evaluate().
  inline __attribute__((always_inline)) void tick(uint32_t now) {
    if (mode_ == RUNNING && !haltPending() && (int32_t)(now - phaseEnd_) < 0) {
      evaluate(now);
#if MAXL_EVAL_PREPARE
      if (!nextChecked_) prepareNext();  // once per segment, in an ordinary tick
#endif
      return;
    }
    advance(now);
  }

  // ---- state
  Mode mode() const { return mode_; }
  uint8_t statusState() const;  // protocol STATUS.state
  bool moving() const { return mode_ == RUNNING || mode_ == BRAKING; }
  bool headStarted() const { return headStarted_; }
  // Positions at the last tick, units of 2^-16 mm, for slots < activeSlots().
  int32_t position(uint8_t slot) const { return pos_[slot]; }
  const int32_t* positions() const { return pos_; }
  // Slots in use: one more than the highest subscribed position slot.
  uint8_t activeSlots() const { return activeSlots_; }
  void setActiveSlots(uint8_t n) { activeSlots_ = n; }
  // How many slots have a known position (set by a GEOMETRY p0).
  uint8_t knownSlots() const { return knownSlots_; }
  // Path speed L·σ' (mm/s) and acceleration L·σ'' (mm/s²) at `now` (≥ the last tick).
  float velocity(uint32_t now);
  float acceleration(uint32_t now);
  // Where the device is, for STATUS: segment id and σ along it.
  void where(uint32_t now, uint16_t& segmentId, float& sigma);

  // ---- queue, for the message handlers
  SegmentQueue& queue() { return queue_; }
  const SegmentQueue& queue() const { return queue_; }
  // Starting position of the head segment (its p0), per slot.
  int32_t base(uint8_t slot) const { return base_[slot]; }
  // p0 of the segment at queue position i.
  int32_t startOf(uint8_t i, uint8_t slot) const { return i == 0 ? base_[slot] : queue_.at((uint8_t)(i - 1)).p1[slot]; }
  // Sets the queue's starting position (GEOMETRY p0 on an empty queue).
  void setBase(const int32_t* p0, uint8_t slots);
  // Whether any TIMING was accepted in the session since it began or since
  // HALT mode 0: a TIMING without start with no timed segment queued then
  // continues timing that is over (late), not nothing (malformed).
  bool timingGiven() const { return timingGiven_; }

  float stopDecel() const { return stopDecel_; }
  // Set it before markTimed(): a new deceleration drops what markTimed() prepared.
  void setStopDecel(float d) {
    stopDecel_ = d;
#if MAXL_EVAL_PREPARE
    endKnown_ = false;
#endif
  }
  // The first n queued segments have timing (queue().markTimed(n)). With
  // MAXL_EVAL_PREPARE the float work of the last one's end is done now, outside
  // the evaluation: whether the timing runs out at rest there (L·σ'(T) against
  // stopDecel), so finishing a segment inside tick() stays integer work unless
  // it has to brake (without it, that evaluation does it). Anything that gives
  // timing calls this, not the queue's markTimed().
  void markTimed(uint8_t n);
  // Called when the queue's timed prefix grew (the handler marked it).
  void timingAdded() { timingGiven_ = true; }

  // True when the current phase (or brake piece) began exactly at t.
  bool phaseStartedAt(uint32_t t) const { return moving() && phaseStart_ == t; }

  // ---- commands; call tick(now) first
  void haltNow(uint32_t now);                  // HALT mode 0
#if MAXL_HALT_BRAKE
  bool haltBrakeAt(uint32_t now, uint32_t at);  // HALT mode 1; false if `at` was past (late)
#endif
  void dropFrom(uint8_t index);                // REPLACE_TAIL, index checked by the caller

  // ---- lookahead (see Lookahead above)
  // Changes whenever the path ahead changes other than by new timing: braking
  // starts or moves to the next piece, a stop, HALT, a new base, a new session.
  uint8_t epoch() const { return epoch_; }
  // HALT mode 1 still ahead: the path is certain only until haltAt().
  bool haltPending() const { return MAXL_HALT_BRAKE && haltPending_; }
#if MAXL_HALT_BRAKE
  uint32_t haltAt() const { return haltAt_; }
#else
  uint32_t haltAt() const { return 0; }
#endif
  // Starts `a` where Motion is now (last tick) and returns the slot's position there.
  int32_t lookFrom(Lookahead& a, uint8_t slot) const;
  // How far `a` can go from `from` in one piece: sets `until` to the end of
  // that piece (a phase, a brake piece, a rest before a timed segment's start,
  // or a pending HALT's time) and returns true, or returns false when the
  // path after `from` is not certain yet (the timing ran out: wait for more,
  // or for Motion to brake; braking: wait for Motion's next piece). At a
  // boundary (until == from) call lookAt(a, slot, from) to cross it.
  bool lookSpan(Lookahead& a, uint8_t slot, uint32_t from, uint32_t& until) const;
  // The slot's position at t (not before the last t asked, not past the
  // `until` of lookSpan), moving `a` on; at a segment's end, exactly its p1.
  int32_t lookAt(Lookahead& a, uint8_t slot, uint32_t t) const;
  // Half acceleration of the slot on the piece `a` is in (Q0.32 units/µs², 0 at rest).
  int32_t lookCurvature(const Lookahead& a) const { return a.state == Lookahead::REST ? 0 : a.track.C; }

  // Sticky: set when the timing ran out while moving (STATUS flag `starved`).
  bool takeStarved() {
    bool s = starved_;
    starved_ = false;
    return s;
  }

 private:
  void enter(uint32_t t, uint8_t k, const int32_t* P, const int32_t* B);
  static float exitSpeedOf(const Segment& s);
  bool endsAtRest(const Segment& s) const;
  void prepareNext();
  void crossPhase(uint32_t t, uint32_t now);
  void finishSegment(uint32_t t, uint32_t now);
  void beginBrake(uint32_t t, float speed, float sigma0, const int32_t* from);
  void finishBrakePiece(uint32_t t);
#if MAXL_HALT_BRAKE
  void brakeFromHalt(uint32_t t);
#endif
  void stopHere(uint16_t segmentId, float sigma);
  void advance(uint32_t now);
  void moveChunkTo(uint32_t t);
  void evaluate(uint32_t now);
  uint32_t nextChunks(uint32_t x);
  void refreshFloatPhase();
  void changed() {
    epoch_++;
    forgetNext();
  }
  // What prepareNext() worked out is for another successor now (or none).
  void forgetNext() {
#if MAXL_EVAL_PREPARE
    nextReady_ = nextChecked_ = false;
#endif
  }
  static void moveTrackTo(FixedTrack& track, uint32_t& chunkStart, uint32_t t);
  int32_t restPosition(uint16_t segmentId, uint8_t slot) const;

  // reset() sets every member from mode_ on to zero (one fill): keep the
  // queue first, mode_ next, and zero a valid start for whatever is added.
  SegmentQueue queue_;
  Mode mode_;
  uint8_t activeSlots_;
  uint8_t knownSlots_;
  uint8_t phase_;          // current phase of the head (RUNNING)
  bool headStarted_ : 1;   // the head has been run or braked along
  bool starved_ : 1;
  bool haltPending_ : 1;   // HALT mode 1 with `at` still ahead
  bool timingGiven_ : 1;   // see timingGiven()
  bool floatValid_ : 1;    // phaseSigma_/phaseNu_ are those of the current phase
  bool brakeStops_ : 1;
#if MAXL_EVAL_PREPARE
  bool endKnown_ : 1;      // endId_ ends at rest or not: endAtRest_ (markTimed(), MAXL_EVAL_PREPARE)
  bool endAtRest_ : 1;
  // Work spread ahead (prepareNext()): the tracks of the segment after the
  // head at the end of its phase 0, worked out in an ordinary tick, so that the
  // tick in which one segment ends, the next starts and that one's short first
  // phase ends too (phases of a few µs, from rounding, are common) does not do
  // that phase's multiplies as well (finishSegment()). MAXL_EVAL_PREPARE (config.h).
  bool nextChecked_ : 1;   // prepareNext() has run for the head's successor
  bool nextReady_ : 1;     // nextP_ and nextB_ hold them
  uint8_t nextLow_;        // low byte of the id of the segment they are for
  int32_t nextP_[MAXL_POSITION_SLOTS];  // each slot's P and B there
  int32_t nextB_[MAXL_POSITION_SLOTS];
#endif
  uint8_t epoch_;
#if MAXL_EVAL_PREPARE
  uint16_t endId_;         // the last timed segment when markTimed() ran
#endif
  uint16_t lastId_;        // where the device is when not moving
  float lastSigma_;
#if MAXL_HALT_BRAKE
  uint16_t haltSegment_;
  uint32_t haltAt_;
#endif
  uint32_t chunkStart_;
  uint32_t phaseStart_;
  uint32_t phaseEnd_;
  float stopDecel_;
  float length_;           // L of the segment being run
  float phaseSigma_;       // σ at the phase start
  float phaseNu_;          // σ' at the phase start, 1/s
  float phaseAcc_;         // σ'' in the phase, 1/s²
  float brakeEndSigma_;    // σ where the current brake piece ends
  float brakeExitSpeed_;   // mm/s when it leaves the segment
  FixedTrack track_[MAXL_POSITION_SLOTS];
  int32_t pos_[MAXL_POSITION_SLOTS];
  int32_t base_[MAXL_POSITION_SLOTS];
};

}  // namespace maxl_fw

#endif
