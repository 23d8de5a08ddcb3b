// Compile-time capacities of the MAXL reader library.
//
// Every buffer is sized here, at compile time: the library never allocates.
// Override any of these with a build flag (-DMAXL_SEGMENT_CAPACITY=64) or by
// editing this file. Defaults follow the board's RAM: an ATmega328P (2 KB) gets
// small queues that leave >= 25 % of RAM free in every example; bigger AVRs,
// ARM boards, the host tests and the wasm simulator get the paper's 64 segments.
#ifndef MAXL_CONFIG_H
#define MAXL_CONFIG_H

#include <stdint.h>

#include "maxl/hal/platform.h"

#if defined(__AVR__)
#include <avr/io.h>
#if RAMEND <= 0x8FF
#define MAXL_SMALL_RAM 1  // ATmega328P / 168 class: 2 KB or less
#endif
#endif

#ifndef MAXL_SMALL_RAM
#define MAXL_SMALL_RAM 0
#endif

// Segments the device can hold: timed ones plus provisional geometry (protocol §6).
#ifndef MAXL_SEGMENT_CAPACITY
#if MAXL_SMALL_RAM
#define MAXL_SEGMENT_CAPACITY 10
#else
#define MAXL_SEGMENT_CAPACITY 64
#endif
#endif

// Event-track changes the device can hold, over all event slots.
#ifndef MAXL_EVENT_CAPACITY
#if MAXL_SMALL_RAM
#define MAXL_EVENT_CAPACITY 12
#else
#define MAXL_EVENT_CAPACITY 128
#endif
#endif

// Position slots (protocol §4, SUBSCRIBE): how many distinct position tracks
// one device can follow. A CoreXY plotter needs 2.
#ifndef MAXL_POSITION_SLOTS
#if MAXL_SMALL_RAM
#define MAXL_POSITION_SLOTS 2
#else
#define MAXL_POSITION_SLOTS 6
#endif
#endif

// Event slots: distinct event tracks one device can follow (each costs RAM on a
// small board). The LightPainter example follows 3 (bitmap, colour, cruise speed)
// and raises it in its build_flags.txt; the default keeps 2.
#ifndef MAXL_EVENT_SLOTS
#if MAXL_SMALL_RAM
#define MAXL_EVENT_SLOTS 2
#else
#define MAXL_EVENT_SLOTS 8
#endif
#endif

// Values per sample a sensor writer may declare.
#ifndef MAXL_MAX_SENSOR_CHANNELS
#define MAXL_MAX_SENSOR_CHANNELS 8
#endif

// A sensor batch is sent once it is this old even if it is not full (µs).
#ifndef MAXL_SAMPLE_MAX_AGE_US
#define MAXL_SAMPLE_MAX_AGE_US 20000UL
#endif

// STATUS is sent at least this often while the device is not idle (µs).
#ifndef MAXL_STATUS_PERIOD_US
#define MAXL_STATUS_PERIOD_US 100000UL
#endif

// The clock-jump check (docs/protocol.md §6 "Clock jumps", firmware/README.md):
// while the device runs or waits for timing, two successive loop() reads of
// micros() must differ by 0..MAXL_CLOCK_JUMP_US µs. A free-running counter
// never runs backwards, and between two loop() calls it advances by the
// longest loop() times (1 + its rate error): the step lead below already
// requires loop() to come back within MAXL_STEP_LEAD_US (3 ms), and a crystal's
// or resonator's rate error (< 0.5 %) adds under 15 µs to that, so 10 ms leaves
// room for a sketch's own work. Outside that the counter jumped: the device
// mends its clock (the loop is taken to have lasted no time), takes no more
// timing, and says so (STATUS flag `clock jump`). 0 leaves the check out.
#ifndef MAXL_CLOCK_JUMP_US
#define MAXL_CLOCK_JUMP_US 10000UL
#endif

// Bytes of a STATUS or SAMPLES frame handed to the serial port per loop()
// (0: the whole frame at once). Pacing keeps one loop() short, so steps stay
// on time while a report goes out. Replies to the author's frames are always
// written at once.
#ifndef MAXL_TX_BYTES_PER_LOOP
#if defined(__AVR__)
#define MAXL_TX_BYTES_PER_LOOP 2
#else
#define MAXL_TX_BYTES_PER_LOOP 0
#endif
#endif

// Most steps one stepper emits per evaluation. Real motion needs a few at most
// (64 per 50 µs loop is 1.3 million steps/s); the bound only matters when a
// bogus position jump would ask for millions at once: the device then catches
// up over the following loops instead of freezing.
#ifndef MAXL_MAX_STEPS_PER_EVALUATION
#define MAXL_MAX_STEPS_PER_EVALUATION 64
#endif

// ---- Step timing from a timer interrupt (readers/step_timer.h)
// 1 where the library has a step timer: 16 MHz AVRs with Timer 1 (Uno, Nano,
// Mega), and the host (a virtual timer the tests drive). 0 elsewhere (wasm):
// steppers step from loop().
#ifndef MAXL_STEP_TIMER
#if MAXL_HAL_WASM
#define MAXL_STEP_TIMER 0
#elif MAXL_HAL_ARDUINO
#if defined(__AVR__) && defined(OCR1B) && defined(TIMSK1) && defined(F_CPU) && F_CPU == 16000000L
#define MAXL_STEP_TIMER 1
#else
#define MAXL_STEP_TIMER 0
#endif
#else
#define MAXL_STEP_TIMER 1
#endif
#endif

// Whether a MAXL_Stepper uses the step timer unless told otherwise
// (MAXL_Stepper::useStepTimer): on boards, yes; in the host tests, only when asked.
#ifndef MAXL_STEP_TIMER_DEFAULT
#if MAXL_HAL_ARDUINO
#define MAXL_STEP_TIMER_DEFAULT 1
#else
#define MAXL_STEP_TIMER_DEFAULT 0
#endif
#endif

// ---- Features an example may leave out (firmware/README.md, "Compile-time
// options"). Each is on unless the build sets it to 0 (-DMAXL_...=0; the
// examples' build_flags.txt). A sketch that uses a feature left out does not
// compile.

// MAXL_Stepper stepping from loop() (polled), as well as from the step timer.
// 0 keeps only timed stepping: for boards with MAXL_STEP_TIMER, whose sketches
// have at most MAXL_STEP_CHANNELS steppers. Without a step timer steppers can
// only poll, so it stays 1 there.
#ifndef MAXL_STEPPER_POLLING
#define MAXL_STEPPER_POLLING 1
#endif
#if !MAXL_STEPPER_POLLING && !MAXL_STEP_TIMER
#undef MAXL_STEPPER_POLLING
#define MAXL_STEPPER_POLLING 1
#endif

// Work spread ahead of the evaluation (motion.h): in an ordinary evaluation,
// the next segment's tracks at the end of its first phase (prepareNext()), so
// that the evaluation in which one segment ends and the next one's short first
// phase ends too does not also do that phase's multiplies; and, when timing is
// marked (markTimed()), the float work of the last timed segment's end (at rest
// there, or starved?). 0 leaves both out (~900 bytes of flash, 20 bytes of RAM
// on an Uno): the evaluation at a short first phase then costs up to ~1 860
// cycles instead of ~1 240 (the spiral of npm run bench -- firmware, two
// slots), and the one in which the timing runs out ~3 100.
// Sketches whose steppers all step from the step timer do not need it: there an
// evaluation's length does not move any step.
#ifndef MAXL_EVAL_PREPARE
#define MAXL_EVAL_PREPARE 1
#endif

// A transmit buffer of its own (FRAME_BUFFER_SIZE more bytes of RAM). With 0
// (the default) one buffer serves both directions, so a report (SAMPLES,
// STATUS, a paced PONG) waits while a frame is being received; a sensor writer
// whose batch is full then refuses the next sample. A sketch that samples fast
// (the Accelerometer example, 1 kHz) sets it to 1: its reports never wait.
#ifndef MAXL_TX_BUFFER
#define MAXL_TX_BUFFER 0
#endif

// HALT mode 1, "brake along the path from time `at`" (protocol §4, §6). 0
// leaves it out: mode 1 is then answered MALFORMED like an unknown mode. The
// TypeScript author never sends it (it pauses and cancels by planning to rest,
// and stops with mode 0); braking when the timing runs out stays, always.
#ifndef MAXL_HALT_BRAKE
#define MAXL_HALT_BRAKE 1
#endif

// Steppers the timer serves; more step from loop() (with MAXL_STEPPER_POLLING).
#ifndef MAXL_STEP_CHANNELS
#define MAXL_STEP_CHANNELS 3
#endif

// Runs (planned windows of steps) each stepper keeps ahead of its timer.
#ifndef MAXL_STEP_RING
#if MAXL_SMALL_RAM
#define MAXL_STEP_RING 4
#else
#define MAXL_STEP_RING 8
#endif
#endif

// How far ahead of the device clock loop() plans steps (µs). It must cover
// the longest loop() (a TIMING frame's float maths, ~1.5 ms on an Uno) and
// stays well under the author's lead time (2 ms + 2 round trips or more).
#ifndef MAXL_STEP_LEAD_US
#define MAXL_STEP_LEAD_US 3000UL
#endif

// Window lengths (µs, powers of two): the longest, where the path is straight
// in time (cruise), and the shortest, for the sharpest accelerations.
#ifndef MAXL_STEP_WINDOW_MAX_US
#define MAXL_STEP_WINDOW_MAX_US 2048U
#endif
#ifndef MAXL_STEP_WINDOW_MIN_US
#define MAXL_STEP_WINDOW_MIN_US 128U
#endif

// How far a timed window's chord may stray from the path where it bends: at
// most s/2^MAXL_STEP_BEND_SHIFT (s the units per step; readers/stepper.h). A
// step then lags its exact time by at most that over the speed, plus
// MAXL_STEP_LAG_UNITS: 1/2^k of a step period, never early. The bend grows as
// W², so a bound 4× tighter (the shift + 2) halves the windows in a ramp and
// doubles what planning a ramp costs; on the power-of-two grid a shift + 1
// halves them or not, by the acceleration (at 10 000 mm/s² and 80 steps/mm:
// 2 048 µs for s/2, 1 024 µs for s/4 and s/8). s/2 (1) by default: three
// steppers on an Uno at 20 kHz need the longer ramp windows (firmware/README.md,
// Benchmark, round 8); 3 is the s/8 of rounds 1-7 (steps at most 1/8 period
// late, for fewer steppers or lower rates).
#ifndef MAXL_STEP_BEND_SHIFT
#define MAXL_STEP_BEND_SHIFT 1
#endif

// Most steps one window may hold: where a window would hold more (over
// ~47 kHz in a 2 ms window), it is halved (down to MAXL_STEP_WINDOW_MIN_US).
// The rest of a run's 127 is room for a catch-up burst.
#ifndef MAXL_STEP_WINDOW_STEPS
#define MAXL_STEP_WINDOW_STEPS 96
#endif

// Every planned step lags its exact position by at least this (units of
// 2^-16 mm), to cover the fixed-point evaluation's error against the exact
// path (firmware/README.md: 8 units plus a few over a segment), so no step
// ever comes early.
#ifndef MAXL_STEP_LAG_UNITS
#define MAXL_STEP_LAG_UNITS 16
#endif

// Timer ticks (0.5 µs): a step pulse's high time is at least
// (MAXL_STEP_PULSE_TICKS - 1) ticks, and a compare is never set closer than
// MAXL_STEP_MIN_TICKS to the count (so it cannot be missed).
#ifndef MAXL_STEP_PULSE_TICKS
#define MAXL_STEP_PULSE_TICKS 5
#endif
#ifndef MAXL_STEP_MIN_TICKS
#define MAXL_STEP_MIN_TICKS 4
#endif

// Serial rate used by MAXL_Device::begin(port) when none is given. 250 000
// baud is exact at 16 MHz; native-USB boards ignore it.
#ifndef MAXL_DEFAULT_BAUD
#define MAXL_DEFAULT_BAUD 250000UL
#endif

#if MAXL_SEGMENT_CAPACITY < 2 || MAXL_SEGMENT_CAPACITY > 255
#error "MAXL_SEGMENT_CAPACITY must be 2..255 (it travels as a u8)"
#endif
#if MAXL_EVENT_CAPACITY < 1 || MAXL_EVENT_CAPACITY > 255
#error "MAXL_EVENT_CAPACITY must be 1..255 (it travels as a u8)"
#endif
#if MAXL_POSITION_SLOTS < 1 || MAXL_POSITION_SLOTS > 14
#error "MAXL_POSITION_SLOTS must be 1..14 (a GEOMETRY payload holds at most 14 positions)"
#endif
#if MAXL_EVENT_SLOTS < 1 || MAXL_EVENT_SLOTS > 32
#error "MAXL_EVENT_SLOTS must be 1..32"
#endif

#if MAXL_STEP_WINDOW_STEPS < 1 || MAXL_STEP_WINDOW_STEPS > 120
#error "MAXL_STEP_WINDOW_STEPS must be 1..120 (a run holds 127 steps)"
#endif
#if MAXL_STEP_BEND_SHIFT < 1 || MAXL_STEP_BEND_SHIFT > 8
#error "MAXL_STEP_BEND_SHIFT must be 1..8 (the bend at most s/2 .. s/256)"
#endif
#if MAXL_STEP_RING < 2 || MAXL_STEP_RING > 32
#error "MAXL_STEP_RING must be 2..32"
#endif
#if (MAXL_STEP_WINDOW_MAX_US & (MAXL_STEP_WINDOW_MAX_US - 1)) || (MAXL_STEP_WINDOW_MIN_US & (MAXL_STEP_WINDOW_MIN_US - 1)) || \
    MAXL_STEP_WINDOW_MIN_US > MAXL_STEP_WINDOW_MAX_US || MAXL_STEP_WINDOW_MAX_US > 2048
#error "MAXL_STEP_WINDOW_MIN_US and _MAX_US must be powers of two, min <= max <= 2048 (step_generator.cpp)"
#endif

#define MAXL_FW_MAJOR 0
#define MAXL_FW_MINOR 1
#define MAXL_FW_PATCH 0

#endif
