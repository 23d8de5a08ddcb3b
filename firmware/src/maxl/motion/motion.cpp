#include "maxl/motion/motion.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "maxl/motion/profile.h"
#include "maxl/time/wrap.h"
#include "maxl/wire/protocol.h"

namespace maxl_fw {

__attribute__((noinline)) int32_t mulhi16Cold(int32_t a, uint16_t x) { return mulhi16(a, x); }

namespace {
inline int32_t signedCoefficient(int8_t sign, int32_t magnitude) {
  return sign > 0 ? magnitude : sign < 0 ? -magnitude : 0;
}
inline int32_t wrapAdd(int32_t a, int32_t b) { return (int32_t)((uint32_t)a + (uint32_t)b); }
// p1 - p0 as a float, without overflowing 32 bits.
inline float deltaOf(int32_t p0, int32_t p1) { return (float)((int64_t)p1 - (int64_t)p0); }
}  // namespace

// Every member after the queue starts at zero (IDLE, false, 0, 0.0f: IEEE
// zero is all zero bytes), so one fill clears them, ~60 bytes of AVR code
// where a store per member took ~400; the epoch alone goes on (changed()), so a
// lookahead from before the reset is stale. motion.h keeps mode_ the first of
// them, after the queue.
__attribute__((noinline)) void Motion::reset() {
  static_assert(offsetof(Motion, mode_) >= offsetof(Motion, queue_) + sizeof(SegmentQueue),
                "reset() clears from mode_ to the end: the queue must come before it");
  uint8_t epoch = epoch_;
  queue_.clear(0);
  memset(&mode_, 0, sizeof(Motion) - offsetof(Motion, mode_));
  epoch_ = (uint8_t)(epoch + 1);
}

uint8_t Motion::statusState() const {
  switch (mode_) {
    case WAITING:
    case RUNNING: return state::RUNNING;
    case BRAKING: return state::BRAKING;
    case STOPPED: return state::STOPPED;
    case HALTED: return state::HALTED;
    default: return state::IDLE;
  }
}

void Motion::setBase(const int32_t* p0, uint8_t slots) {
  changed();
  for (uint8_t i = 0; i < slots; i++) {
    base_[i] = p0[i];
    if (!moving()) pos_[i] = p0[i];
  }
  knownSlots_ = slots;
}

// ------------------------------------------------------------------ tick

// The slow path of tick(): everything but "inside the current phase".
void Motion::advance(uint32_t now) {
  // Each pass either evaluates and returns, or crosses one boundary that is
  // not after `now` (a phase, a segment, a brake piece); the queue is finite.
  for (;;) {
    switch (mode_) {
      case IDLE:
      case STOPPED:
      case HALTED:
        if (queue_.timed() == 0) return;
        mode_ = WAITING;
        break;
      case WAITING: {
        if (queue_.timed() == 0) {
          mode_ = IDLE;
          return;
        }
        uint32_t start = queue_.head().start;
        if (timeBefore(now, start)) return;
        enter(start, 0, base_, queue_.head().b0);
        break;
      }
      case RUNNING:
#if MAXL_HALT_BRAKE
        if (haltPending_ && haltSegment_ == queue_.headId() && timeBefore(haltAt_, phaseEnd_)) {
          if (timeBefore(now, haltAt_)) {
            evaluate(now);
            return;
          }
          brakeFromHalt(haltAt_);
          break;
        }
#endif
        if (timeBefore(now, phaseEnd_)) {
          evaluate(now);
          return;
        }
        crossPhase(phaseEnd_, now);
        break;
      case BRAKING:
        if (timeBefore(now, phaseEnd_)) {
          evaluate(now);
          return;
        }
        finishBrakePiece(phaseEnd_);
        break;
    }
  }
}

// The hot path: position of every active slot at `now`, inside the current
// phase or brake piece.
void Motion::evaluate(uint32_t now) {
  uint32_t x = now - chunkStart_;
  if (x >> 16) x = nextChunks(x);  // once every 65 ms at most
  uint16_t x16 = (uint16_t)x;
  const FixedTrack* track = track_;
  int32_t* pos = pos_;
  for (uint8_t n = activeSlots_; n; n--) *pos++ = (track++)->at(x16);
}

// Moves the chunk start on by whole 2^16 µs until `x` (µs since it) is below
// 2^16; returns the new x.
__attribute__((noinline)) uint32_t Motion::nextChunks(uint32_t x) {
  while (x >= 65536UL) {
    for (uint8_t i = 0; i < activeSlots_; i++) track_[i].nextChunk();
    chunkStart_ += 65536UL;
    x -= 65536UL;
  }
  return x;
}

// Moves every slot's chunk start to t (>= chunkStart_), keeping position and
// velocity continuous: whole 2^16 µs first (nextChunks, rare), then the rest.
void Motion::moveChunkTo(uint32_t t) {
  uint32_t x = t - chunkStart_;
  if (x >> 16) x = nextChunks(x);
  if (x) {
    FixedTrack* track = track_;
    for (uint8_t n = activeSlots_; n; n--) (track++)->advance((uint16_t)x);
    chunkStart_ = t;
  }
}

// The same for one track (the lookahead's): the same operations in the same
// order, so the same numbers.
__attribute__((noinline)) void Motion::moveTrackTo(FixedTrack& track, uint32_t& chunkStart, uint32_t t) {
  uint32_t x = t - chunkStart;
  while (x >= 65536UL) {
    track.nextChunk();
    chunkStart += 65536UL;
    x -= 65536UL;
  }
  if (x) {
    track.advance((uint16_t)x);
    chunkStart = t;
  }
}

// Starts phase k of the head at t with each slot's P and B (phase 0 at the
// segment's start: base_, the previous p1, and b0); C = ±cmag or 0 as the
// phase is.
void Motion::enter(uint32_t t, uint8_t k, const int32_t* P, const int32_t* B) {
  const Segment& s = queue_.head();
  int8_t sign = s.phaseSign(k);
  FixedTrack* track = track_;
  const int32_t* cmag = s.cmag;
  for (uint8_t n = activeSlots_; n; n--, track++) {
    track->P = *P++;
    track->B = *B++;
    track->C = signedCoefficient(sign, *cmag++);
  }
  forgetNext();  // prepare for the segment after this one
  phase_ = k;
  chunkStart_ = phaseStart_ = t;
  phaseEnd_ = t + s.durations[k];
  length_ = s.length;
  floatValid_ = false;
  headStarted_ = true;
  mode_ = RUNNING;
}

#if MAXL_EVAL_PREPARE
// In an ordinary tick of the head (tick()), for the timed segment after it with
// more than one phase and a phase 0 shorter than 2^16 µs: every slot's position
// and velocity (P and B) at the end of that phase 0, as enter() and crossPhase() would compute them
// there (the same FixedTrack operations from the same P, B and C), so the same
// numbers. finishSegment() uses them (enter(…, 1, nextP_, nextB_)) when that phase is
// over by the time the head ends; markTimed(), changed() and dropFrom() ask again.
__attribute__((noinline)) void Motion::prepareNext() {
  nextChecked_ = true;
  if (queue_.timed() < 2) return;
  const Segment& n = queue_.at(1);
  if (n.phaseCount < 2 || (n.durations[0] >> 16)) return;
  const Segment& h = queue_.head();
  uint16_t d0 = (uint16_t)n.durations[0];
  int8_t sign = n.phaseSign(0);
  for (uint8_t i = 0; i < activeSlots_; i++) {
    FixedTrack k;  // as enter(start, 0, …): P = base_ = the head's p1, B = b0, C = ±cmag
    k.P = h.p1[i];
    k.B = n.b0[i];
    k.C = signedCoefficient(sign, n.cmag[i]);
    k.advance(d0);
    nextP_[i] = k.P;
    nextB_[i] = k.B;
  }
  nextLow_ = (uint8_t)(queue_.headId() + 1);
  nextReady_ = true;
}
#endif

// Into the next phase at t (≤ now), or to the segment's end.
void Motion::crossPhase(uint32_t t, uint32_t now) {
  const Segment& s = queue_.head();
  uint8_t next = (uint8_t)(phase_ + 1);
  if (next >= s.phaseCount) {
    finishSegment(t, now);
    return;
  }
  if (next + 1 == s.phaseCount && !haltPending()) {
    // Into the last phase: if it is over by `now` too (a last phase of a few
    // µs), the segment ends exactly at its p1 whatever the phase does, so go
    // straight there without moving the tracks through it.
    uint32_t end = t + s.durations[next];
    if (!timeBefore(now, end)) {
      finishSegment(end, now);
      return;
    }
  }
  moveChunkTo(t);
  phase_++;
  int8_t sign = s.phaseSign(phase_);
  for (uint8_t i = 0; i < activeSlots_; i++) track_[i].C = signedCoefficient(sign, s.cmag[i]);
  phaseStart_ = t;
  phaseEnd_ = t + s.durations[phase_];
  floatValid_ = false;
}

// The head's timing is over at t (≤ now): it ends exactly at its p1.
void Motion::finishSegment(uint32_t t, uint32_t now) {
  (void)now;  // used by MAXL_EVAL_PREPARE
  const Segment& s = queue_.head();
  {
    int32_t* pos = pos_;
    int32_t* base = base_;
    const int32_t* p1 = s.p1;
    for (uint8_t n = activeSlots_; n; n--) *pos++ = *base++ = *p1++;
  }
  bool moreTiming = queue_.timed() > 1;
  lastId_ = queue_.headId();
  lastSigma_ = 1.0f;
  if (moreTiming) {
    queue_.popHead();
    headStarted_ = false;
    // A streamed path is contiguous: the next one usually starts right here,
    // and starts now (what tick()'s next pass would do from WAITING).
    const Segment& next = queue_.head();
    if (next.start != t)
      mode_ = WAITING;
#if MAXL_EVAL_PREPARE
    else if (nextReady_ && nextLow_ == (uint8_t)queue_.headId() && !timeBefore(now, t + next.durations[0]))
      // Its phase 0 is over too: straight into phase 1 with what prepareNext()
      // worked out, the numbers crossPhase() would compute, without the multiplies.
      enter(t + next.durations[0], 1, nextP_, nextB_);
#endif
    else
      enter(t, 0, base_, next.b0);
    return;
  }
  // The last timed segment: at rest at its end, or starved. With
  // MAXL_EVAL_PREPARE markTimed() has usually answered that already (the same
  // floats, so the same answer).
#if MAXL_EVAL_PREPARE
  bool known = endKnown_ && endId_ == lastId_;
  bool knownAtRest = endAtRest_;
#else
  const bool known = false, knownAtRest = false;
#endif
  float exitSpeed = known && knownAtRest ? 0.0f : exitSpeedOf(s);
  bool rest = known ? knownAtRest : atRest(exitSpeed, stopDecel_);
  queue_.popHead();
  headStarted_ = false;
  if (rest) {
    mode_ = IDLE;
    return;
  }
  // Timing ran out while moving (protocol §6): brake along the provisional
  // geometry, or stop dead at the end of the path if there is none.
  starved_ = true;
  if (queue_.count() > 0)
    beginBrake(t, exitSpeed, 0.0f, base_);
  else
    stopHere(lastId_, 1.0f);
}

void Motion::markTimed(uint8_t n) {
  queue_.markTimed(n);
#if MAXL_EVAL_PREPARE
  if (!nextReady_) nextChecked_ = false;  // the head's successor may have timing now
  endKnown_ = n > 0;
  if (!endKnown_) return;
  endId_ = (uint16_t)(queue_.headId() + n - 1);
  endAtRest_ = endsAtRest(queue_.at((uint8_t)(n - 1)));
#endif
}

// L·σ'(T): the speed at the end of s, mm/s.
__attribute__((noinline)) float Motion::exitSpeedOf(const Segment& s) { return s.length * exitNu(s); }

// Whether the timing running out at the end of s leaves the device at rest.
bool Motion::endsAtRest(const Segment& s) const { return atRest(exitSpeedOf(s), stopDecel_); }

// Starts braking at time t along the head segment, from `speed` mm/s at σ =
// sigma0, with positions `from` (which may be base_ or pos_).
//
// Along the segment the path length braked so far is s(τ) = v·τ − D·τ²/2, so
// slot i, which moves Δi/L units per mm, is at from_i + (Δi/L)·s(τ):
//   B = (Δi/L)·v  and  C = −(Δi/L)·D/2, scaled as in fixed_point.h.
void Motion::beginBrake(uint32_t t, float speed, float sigma0, const int32_t* from) {
  changed();
  const Segment& s = queue_.head();
  headStarted_ = true;
  queue_.markTimed(0);  // any timing it had is abandoned
  if (from != pos_)
    for (uint8_t i = 0; i < activeSlots_; i++) pos_[i] = from[i];
  float length = s.length;
  float decel = stopDecel_;
  // A speed that is not a positive finite number (absurd timing) stops here.
  if (!(decel > 0.0f) || !(speed > 0.0f) || !isFiniteFloat(speed) || atRest(speed, decel)) {
    stopHere(queue_.headId(), sigma0);
    return;
  }
  BrakePiece piece = planBrake(speed, decel, (1.0f - sigma0) * length);
  // A dwell (length 0) is a point of the path: the brake piece along it covers
  // nothing and lasts 0 µs, and braking goes on along the next segment at the
  // same speed. Its slots do not move (Δ = 0), so 1/L is never needed there.
  float perLength = length > 0.0f ? 1.0f / length : 0.0f;
  for (uint8_t i = 0; i < activeSlots_; i++) {
    float perMm = deltaOf(base_[i], s.p1[i]) * perLength;
    float b = perMm * speed * B_SCALE;
    float c = -perMm * decel * 0.5f * C_SCALE;
    if (!(fabsf(b) < FIXED_LIMIT) || !(fabsf(c) < FIXED_LIMIT)) {
      // Geometry too steep for the fixed-point range: stop where we are.
      stopHere(queue_.headId(), sigma0);
      return;
    }
    track_[i].P = pos_[i];
    track_[i].B = roundToInt(b);
    track_[i].C = roundToInt(c);
  }
  brakeStops_ = piece.stops;
  brakeEndSigma_ = piece.stops ? sigma0 + piece.distance * perLength : 1.0f;
  if (brakeEndSigma_ > 1.0f) brakeEndSigma_ = 1.0f;
  brakeExitSpeed_ = piece.exitSpeed;
  chunkStart_ = phaseStart_ = t;
  phaseEnd_ = t + piece.duration;
  length_ = length;
  phaseSigma_ = sigma0;
  phaseNu_ = speed * perLength;
  phaseAcc_ = -decel * perLength;
  floatValid_ = true;
  mode_ = BRAKING;
}

void Motion::finishBrakePiece(uint32_t t) {
  const Segment& s = queue_.head();
  if (brakeStops_) {
    // At rest inside the segment, at σ = σ0 + v²/(2·D·L): the same point on
    // every device, whatever its clock, so it is set from σ, not integrated.
    for (uint8_t i = 0; i < activeSlots_; i++)
      pos_[i] = wrapAdd(base_[i], roundToInt(deltaOf(base_[i], s.p1[i]) * brakeEndSigma_));
    stopHere(queue_.headId(), brakeEndSigma_);
    return;
  }
  for (uint8_t i = 0; i < activeSlots_; i++) pos_[i] = base_[i] = s.p1[i];
  lastId_ = queue_.headId();
  lastSigma_ = 1.0f;
  queue_.popHead();
  headStarted_ = false;
  if (queue_.count() > 0)
    beginBrake(t, brakeExitSpeed_, 0.0f, base_);
  else
    stopHere(lastId_, 1.0f);  // out of provisional geometry while still moving
}

#if MAXL_HALT_BRAKE
// HALT mode 1 reached its time t inside the running head segment.
void Motion::brakeFromHalt(uint32_t t) {
  moveChunkTo(t);
  for (uint8_t i = 0; i < activeSlots_; i++) pos_[i] = track_[i].P;
  refreshFloatPhase();
  float tau = (float)(t - phaseStart_) * 1e-6f;
  float sigma = phaseSigma_ + tau * (phaseNu_ + 0.5f * phaseAcc_ * tau);
  float speed = length_ * (phaseNu_ + phaseAcc_ * tau);
  if (sigma > 1.0f) sigma = 1.0f;
  if (speed < 0.0f) speed = 0.0f;
  haltPending_ = false;
  beginBrake(t, speed, sigma, pos_);
}
#endif

void Motion::stopHere(uint16_t segmentId, float sigma) {
  changed();
  mode_ = STOPPED;
  lastId_ = segmentId;
  lastSigma_ = sigma;
  haltPending_ = false;
}

// ------------------------------------------------------------------ lookahead

int32_t Motion::lookFrom(Lookahead& a, uint8_t slot) const {
  a.epoch = epoch_;
  a.segment = queue_.headId();
  a.phase = phase_;
  a.chunkStart = chunkStart_;
  a.pieceEnd = phaseEnd_;
  a.track = track_[slot];
  a.state = mode_ == RUNNING ? Lookahead::RUN : mode_ == BRAKING ? Lookahead::BRAKE : Lookahead::REST;
  return pos_[slot];
}

// Where a slot rests before segment `segmentId` starts: the p1 of the one
// before it, or, for the head, its p0 while Motion runs or brakes along it and
// Motion's own position when it is at rest (stopped inside a segment, halted).
int32_t Motion::restPosition(uint16_t segmentId, uint8_t slot) const {
  uint16_t i = (uint16_t)(segmentId - queue_.headId());
  if (i == 0 || i > queue_.count()) return moving() ? base_[slot] : pos_[slot];
  return queue_.at((uint8_t)(i - 1)).p1[slot];
}

bool Motion::lookSpan(Lookahead& a, uint8_t slot, uint32_t from, uint32_t& until) const {
  if (a.epoch != epoch_) return false;
  // Each pass either answers or crosses one boundary at or before `from`.
  for (;;) {
    if (a.state == Lookahead::BRAKE) {  // only the piece Motion is in
      until = a.pieceEnd;
      return timeBefore(from, until);
    }
    int16_t i = queue_.find(a.segment);
    if (i < 0 || i >= queue_.timed()) return false;  // no timing for it (yet)
    const Segment& s = queue_.at((uint8_t)i);
    if (a.state == Lookahead::REST) {
      until = s.start;
      if (timeBefore(from, until)) return true;
      // it starts: as Motion::enter(start, 0, …), then phase 0 below
      a.track.P = startOf((uint8_t)i, slot);
      a.track.B = s.b0[slot];
      a.chunkStart = a.pieceEnd = s.start;
      a.phase = 0xFF;
      a.state = Lookahead::RUN;
    } else {
#if MAXL_HALT_BRAKE
      if (haltPending() && haltSegment_ == a.segment && timeBefore(haltAt_, a.pieceEnd)) {
        // Motion brakes at haltAt_: what follows is Motion's to decide.
        until = haltAt_;
        return timeBefore(from, until);
      }
#endif
      until = a.pieceEnd;
      if (timeBefore(from, until)) return true;
      if (a.phase + 1 >= s.phaseCount) {  // the segment ends: rest at its p1 until the next starts
        a.segment++;
        a.state = Lookahead::REST;
        continue;
      }
      moveTrackTo(a.track, a.chunkStart, a.pieceEnd);  // as Motion::crossPhase()
    }
    a.phase++;
    a.track.C = signedCoefficient(s.phaseSign(a.phase), s.cmag[slot]);
    a.pieceEnd += s.durations[a.phase];
  }
}

int32_t Motion::lookAt(Lookahead& a, uint8_t slot, uint32_t t) const {
  if (a.state == Lookahead::REST) return restPosition(a.segment, slot);
  if (t == a.pieceEnd && a.state == Lookahead::RUN) {
    // a segment ends exactly at its p1, as in Motion::finishSegment(). (Where a
    // brake piece ends, Motion sets the position too; the lookahead learns it
    // when it starts again from Motion, and the planner catches up.)
    int16_t i = queue_.find(a.segment);
    if (i >= 0 && a.phase + 1 >= queue_.at((uint8_t)i).phaseCount) return queue_.at((uint8_t)i).p1[slot];
  }
  if (timeBefore(t, a.chunkStart)) t = a.chunkStart;
  uint32_t x = t - a.chunkStart;
  while (x >= 65536UL) {
    a.track.nextChunk();
    a.chunkStart += 65536UL;
    x -= 65536UL;
  }
  // FixedTrack::at(), with the multiply out of line (the same numbers)
  const FixedTrack& k = a.track;
  int32_t w = (int32_t)((uint32_t)k.B + (uint32_t)mulhi16Cold(k.C, (uint16_t)x));
  return (int32_t)((uint32_t)k.P + (uint32_t)mulhi16Cold(w, (uint16_t)x));
}

// ------------------------------------------------------------------ commands

void Motion::haltNow(uint32_t now) {
  changed();
  uint16_t id;
  float sigma;
  where(now, id, sigma);
  queue_.clear(queue_.nextId());
  for (uint8_t i = 0; i < activeSlots_; i++) base_[i] = pos_[i];
  mode_ = HALTED;
  lastId_ = id;
  lastSigma_ = sigma;
  headStarted_ = false;
  haltPending_ = false;
  timingGiven_ = false;
}

#if MAXL_HALT_BRAKE
bool Motion::haltBrakeAt(uint32_t now, uint32_t at) {
  changed();
  if (timeBefore(at, now)) {
    // Too late for `at`: brake at once.
    if (mode_ == RUNNING) {
      brakeFromHalt(now);
    } else if (mode_ == WAITING) {
      queue_.markTimed(0);
      stopHere(lastId_, lastSigma_);
    } else {
      queue_.markTimed(0);
    }
    return false;
  }
  // Keep the timing of segments that start by `at`; the one running at `at`
  // (start <= at < end) brakes from there, the rest become provisional.
  uint8_t keep = 0;
  while (keep < queue_.timed() && !timeBefore(at, queue_.at(keep).start)) keep++;
  markTimed(keep);
  haltPending_ = false;
  if (keep > 0) {
    const Segment& s = queue_.at((uint8_t)(keep - 1));
    if (timeBefore(at, s.end())) {
      haltPending_ = true;
      haltSegment_ = (uint16_t)(queue_.headId() + keep - 1);
      haltAt_ = at;
    }
  }
  return true;
}
#endif

void Motion::dropFrom(uint8_t index) {
  queue_.truncate(index);
  forgetNext();  // the segment after the head may be another one now
#if MAXL_HALT_BRAKE
  if (haltPending() && (uint16_t)(haltSegment_ - queue_.headId()) >= index) haltPending_ = false;
#endif
}

// ------------------------------------------------------------------ floats on demand

void Motion::refreshFloatPhase() {
  if (floatValid_ || mode_ != RUNNING) return;
  const Segment& s = queue_.head();
  float acc;
  sigmaAt(s, phaseStart_ - s.start, phaseSigma_, phaseNu_, acc);
  phaseAcc_ = (float)s.phaseSign(phase_) * s.alpha;
  floatValid_ = true;
}

namespace {
float clampedSeconds(uint32_t now, uint32_t start, uint32_t end) {
  int32_t in = timeDiff(now, start);
  int32_t len = timeDiff(end, start);
  if (in < 0) in = 0;
  if (in > len) in = len;
  return (float)in * 1e-6f;
}
}  // namespace

float Motion::velocity(uint32_t now) {
  if (!moving()) return 0.0f;
  refreshFloatPhase();
  float tau = clampedSeconds(now, phaseStart_, phaseEnd_);
  float v = length_ * (phaseNu_ + phaseAcc_ * tau);
  return v > 0.0f ? v : 0.0f;
}

float Motion::acceleration(uint32_t now) {
  (void)now;
  if (!moving()) return 0.0f;
  refreshFloatPhase();
  return length_ * phaseAcc_;
}

void Motion::where(uint32_t now, uint16_t& segmentId, float& sigma) {
  if (!moving()) {
    segmentId = lastId_;
    sigma = lastSigma_;
    return;
  }
  segmentId = queue_.headId();
  // Cheap form while running: σ = (p − p0)/Δ on the slot that moves most,
  // from the fixed-point position of the last tick (one float division on an
  // AVR instead of the phase walk below; STATUS runs in loop() at speed, which
  // matters to steppers stepping from loop(): built without polled stepping,
  // the phase walk, once per phase, is all it takes).
#if MAXL_STEPPER_POLLING
  if (mode_ == RUNNING && !floatValid_) {
    const Segment& s = queue_.head();
    float best = 0.0f, moved = 0.0f;
    for (uint8_t i = 0; i < activeSlots_; i++) {
      float delta = deltaOf(base_[i], s.p1[i]);
      if (fabsf(delta) > fabsf(best)) {
        best = delta;
        moved = deltaOf(base_[i], pos_[i]);
      }
    }
    if (fabsf(best) >= 65536.0f) {  // at least 1 mm of travel: σ to better than 1e-5
      sigma = moved / best;
      if (sigma < 0.0f) sigma = 0.0f;
      if (sigma > 1.0f) sigma = 1.0f;
      return;
    }
  }
#endif
  refreshFloatPhase();
  float tau = clampedSeconds(now, phaseStart_, phaseEnd_);
  sigma = phaseSigma_ + tau * (phaseNu_ + 0.5f * phaseAcc_ * tau);
  if (sigma < 0.0f) sigma = 0.0f;
  if (sigma > 1.0f) sigma = 1.0f;
}

}  // namespace maxl_fw
