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

// Event slots: distinct event tracks one device can follow.
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

#define MAXL_FW_MAJOR 0
#define MAXL_FW_MINOR 1
#define MAXL_FW_PATCH 0

#endif
