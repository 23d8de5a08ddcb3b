// Step timing from a timer interrupt (MAXL_STEP_TIMER; on an Uno, Timer 1).
//
// loop() plans steps a few ms ahead (step_planner.h) as runs: `count` steps
// in one direction, the first at `next`, then every `interval`. Each stepper
// has a StepChannel, a small ring of runs. A timer counts 2 ticks per µs of
// the device clock; its compare interrupt emits every step whose time has
// come and sets the compare to the earliest next step of all channels, so a
// loop() that stalls (a STATUS being built, a TIMING's float maths) no longer
// delays steps: it only has to plan faster than real time, on average.
//
// Times are Q16.16 ticks in a u32: the integer part is the 16-bit timer
// count itself (it wraps every 32.768 ms, and so does the u32), the fraction
// keeps `next += interval` exact to 2^-16 tick over a run. `next` is stored
// biased by 0xFFFF, so that its integer part is the ceiling of the exact
// time: a step is never emitted before it. All times in the rings lie within
// a few ms of the timer (the planner plans at most MAXL_STEP_LEAD_US ahead, and
// never more than a few ms behind), so 16-bit signed differences order them.
//
// The interrupt's share of a step: pin high, one 32-bit add, a new compare
// (while the pulse is high), pin low (after MAXL_STEP_PULSE_TICKS). The run
// going out is the channel's `current_`, consumed in place; when it is spent
// the next queued run is copied in. On AVR the vector is one pass of
// assembly over every channel (step_timer.cpp); elsewhere serviceAll() does
// the same in C.
#ifndef MAXL_READERS_STEP_TIMER_H
#define MAXL_READERS_STEP_TIMER_H

#include <stdint.h>
#include <string.h>

#include "maxl/config.h"
#include "maxl/hal/hal.h"

#if MAXL_STEP_TIMER

namespace maxl_fw {

struct StepRun {
  uint32_t next;      // Q16.16 ticks of the next step, biased by 0xFFFF (see above)
  uint32_t interval;  // Q16.16 ticks between steps
  uint8_t count;      // steps left (bits 0..6), BACKWARD (bit 7)

  // The integer part of `next` (the timer count of the next step).
  uint16_t tick() const {
#if defined(__AVR__)
    uint16_t t;
    memcpy(&t, (const uint8_t*)&next + 2, 2);  // little-endian: the high half, two loads
    return t;
#else
    return (uint16_t)(next >> 16);
#endif
  }
};

// One stepper's steps: the run going out (`current_`, first in the object,
// where the AVR vector finds it) and the runs queued behind it,
// MAXL_STEP_RING in all.
class StepChannel {
 public:
  static const uint8_t BACKWARD = 0x80;
  static const uint8_t MAX_RUN = 0x7F;
  static const uint8_t UNKNOWN = 0x01;  // DIR not written yet

  StepChannel() : stepPin(), dirPin(), invert(false), head_(0), count_(0), backward_(UNKNOWN) { current_.count = 0; }

  // Room for another run (the loop's side; the interrupt only frees room).
  uint8_t free() const { return (uint8_t)(MAXL_STEP_RING - count_); }
  bool busy() const { return count_ != 0; }
  // Appends a run; the caller checked free(). `count` 1..MAX_RUN.
  __attribute__((noinline)) void push(uint32_t next, uint32_t interval, uint8_t count, bool backward);
  // Steps still to go out, signed (+ forward).
  int16_t pending() const;
  // Drops every step due at or after `tick` (Q16.16, unbiased) and returns
  // how many went, signed (+ forward). The interrupt must be locked out.
  int16_t dropFrom(uint32_t tick);
  // Drops everything (interrupts locked out); returns dropFrom's count.
  int16_t clear() { return dropAll(); }

  // ---- for StepTimer (interrupts off)
  // Raises STEP and takes the step off the ring if one is due at `now`.
  inline void service(uint16_t now);
  // STEP low, then DIR for the next run.
  inline void finish();
  // The count of the next step, if there is one.
  bool nextDue(uint16_t& at) const {
    if (!count_) return false;
    at = current_.tick();
    return true;
  }

  // The run going out (count_ >= 1), then the stepper's pins (MAXL_StepGenerator
  // keeps them here), then the ring's state. The AVR vector reads every member
  // below at fixed offsets (step_timer.cpp), so they are public; only
  // StepTimer's interrupt writes them besides the methods above.
  StepRun current_;
  maxl_fw::hal::OutputPin stepPin;
  maxl_fw::hal::OutputPin dirPin;
  bool invert;
  volatile uint8_t head_;   // the first queued run
  volatile uint8_t count_;  // runs held: current_ (when >= 1) and count_ − 1 queued
  uint8_t backward_;        // the DIR pin's state: BACKWARD, 0, or UNKNOWN
  static const uint8_t QUEUED = MAXL_STEP_RING - 1;
  StepRun queued_[QUEUED];  // behind current_, from head_

 private:
  int16_t dropAll();
  // The i-th run (0 = current_), i < count_.
  StepRun& run(uint8_t i) {
    if (i == 0) return current_;
    uint8_t j = (uint8_t)(head_ + i - 1);
    return queued_[j >= QUEUED ? (uint8_t)(j - QUEUED) : j];
  }
  const StepRun& run(uint8_t i) const { return const_cast<StepChannel*>(this)->run(i); }
  // current_ is spent: the next queued run takes its place (or none is left).
  inline void promote();
  void setDirection(uint8_t backward);
};

// The timer and the channels it serves.
class StepTimer {
 public:
  // Starts the timer (idempotent) and registers a channel; false when
  // MAXL_STEP_CHANNELS are taken (that stepper stays polled).
  static bool attach(StepChannel* channel);
  static void detach(StepChannel* channel);
  // Count of the timer at device time t (µs) in Q16.16, unbiased.
  static uint32_t ticksAt(uint32_t t) { return (uint32_t)maxl_fw::hal::stepTicks(t) << 16; }
  // Sets the compare after the rings changed (takes the interrupt lock).
  static void kick();
  // The compare interrupt's work in C (serviceAll): the host's virtual timer
  // calls it; on AVR the vector is its assembly form (step_timer.cpp).
  static void interrupt();
  // The same without the pulse hold, which waits for the count to move on:
  // the reference of the vector's check in simavr, with the timer stopped.
  static void interruptWithoutHold();

  // for the interrupt
  static StepChannel* channels_[MAXL_STEP_CHANNELS];
  static uint8_t count_;
  static void arm();
};

}  // namespace maxl_fw

#endif  // MAXL_STEP_TIMER
#endif
