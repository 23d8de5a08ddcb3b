// The hardware layer: everything the library needs from a board.
//
//   micros()        the device clock, a free-running u32 µs counter
//   readByte()      next received link byte, or -1
//   write()         send link bytes
//   OutputPin       a digital output fast enough for step pulses
//   stepPulseWait() the step pulse's high time
//
// Implementations: hal_arduino.cpp, hal_host.cpp (+ hal_host.h for tests),
// hal_wasm.cpp. Each .cpp compiles to nothing on the other platforms.
#ifndef MAXL_HAL_HAL_H
#define MAXL_HAL_HAL_H

#include <stdint.h>

#include "maxl/hal/platform.h"

#if MAXL_HAL_ARDUINO
class Stream;
#endif

#if MAXL_HAL_ARDUINO && defined(__AVR__) && F_CPU == 16000000L
// The Arduino core's Timer 0 overflow counter (wiring.c), for an inline micros().
#include <avr/interrupt.h>
#include <avr/io.h>
extern "C" volatile unsigned long timer0_overflow_count;
#define MAXL_INLINE_MICROS 1
#endif

namespace maxl_fw {
namespace hal {

#if MAXL_INLINE_MICROS
// The core's micros() at 16 MHz, inline: it is read on every loop(), and the
// call costs more than the work (55 cycles to ~30). Timer 0 runs at clk/64,
// so one count is 4 µs: micros = (overflows·256 + TCNT0)·4, counting an
// overflow that is pending but not yet handled.
inline __attribute__((always_inline)) uint32_t micros() {
  uint8_t sreg = SREG;
  cli();
  uint32_t m = timer0_overflow_count;
  uint8_t t = TCNT0;
  if ((TIFR0 & _BV(TOV0)) && t < 255) m++;
  SREG = sreg;
  return ((m << 8) | t) << 2;
}
#else
uint32_t micros();
#endif
int16_t readByte();
void write(const uint8_t* data, uint8_t length);

#if MAXL_HAL_ARDUINO
// The Stream the link runs over (Serial, SerialUSB, ...).
void attach(Stream& stream);
#else
// Host and wasm have one built-in link; a port passed to begin() is ignored.
template <class Port>
inline void attach(Port&) {}
#endif

// A digital output written straight to its port register where the board has
// one (AVR), else through the platform (host log, wasm import).
struct OutputPin {
#if MAXL_HAL_ARDUINO && defined(__AVR__)
  volatile uint8_t* port;
  uint8_t mask;
#endif
  uint8_t number;
  bool valid;
};
void makeOutput(OutputPin& pin, uint8_t number);
#if MAXL_HAL_ARDUINO && defined(__AVR__)
// Inline on AVR: step pulses write it twice per step. The port is shared with
// other pins, so the read-modify-write keeps interrupts out.
inline __attribute__((always_inline)) void writePin(const OutputPin& pin, bool high) {
  if (!pin.valid) return;
  uint8_t sreg = SREG;
  cli();
  if (high)
    *pin.port |= pin.mask;
  else
    *pin.port &= (uint8_t)~pin.mask;
  SREG = sreg;
}
#else
void writePin(const OutputPin& pin, bool high);
#endif

// Holds a step pulse high long enough for common drivers (~2 µs on a real
// board; nothing in virtual time).
void stepPulseWait();
// Direction setup time before a step after the direction pin changed.
void directionSetupWait();

}  // namespace hal
}  // namespace maxl_fw

#endif
