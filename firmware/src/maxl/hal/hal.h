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

#include "maxl/config.h"
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

#if MAXL_STEP_TIMER
// ---- The step timer (readers/step_timer.h): a free-running 16-bit count at
// 2 per µs of the device clock, with one compare interrupt.
//   AVR:  Timer 1 in normal mode at clk/8, OCR1B and TIMER1_COMPB (OCR1A,
//         OC1A and ICR1 stay free for the sketch, on the same count: see
//         MAXL_useTimer1() in MAXL.h).
//   host: a virtual count the tests run with host::runStepTimer().
// Starts the count (idempotent); `isr` is what the compare runs (host only:
// on AVR the vector is in step_timer.cpp).
void stepTimerBegin(void (*isr)());
// The count at device time t (µs): 2·t plus an offset measured at start.
uint16_t stepTicks(uint32_t t);
#if MAXL_HAL_ARDUINO && defined(__AVR__)
inline __attribute__((always_inline)) uint16_t stepTimerNow() { return TCNT1; }  // interrupts off
// Sets the compare to `at`, or MAXL_STEP_MIN_TICKS from now if `at` is
// closer or past (a match on a passed count would come 32 ms late).
inline __attribute__((always_inline)) void stepTimerArm(uint16_t at) {
  uint16_t now = TCNT1;
  if ((int16_t)(at - now) < (int16_t)MAXL_STEP_MIN_TICKS) at = (uint16_t)(now + MAXL_STEP_MIN_TICKS);
  OCR1B = at;
  TIFR1 = _BV(OCF1B);
  TIMSK1 |= _BV(OCIE1B);
}
inline __attribute__((always_inline)) void stepTimerDisarm() { TIMSK1 &= (uint8_t)~_BV(OCIE1B); }
inline __attribute__((always_inline)) uint8_t lockInterrupts() {
  uint8_t sreg = SREG;
  cli();
  return sreg;
}
inline __attribute__((always_inline)) void unlockInterrupts(uint8_t sreg) { SREG = sreg; }
// From the interrupt (interrupts are off): no save and restore.
inline __attribute__((always_inline)) void writePinFromIsr(const OutputPin& pin, bool high) {
  if (high)
    *pin.port |= pin.mask;
  else
    *pin.port &= (uint8_t)~pin.mask;
}
// Holds a step pulse: returns once the count is MAXL_STEP_PULSE_TICKS past
// `since` (read just after the pin rose): at least 2 µs high.
inline __attribute__((always_inline)) void stepPulseHold(uint16_t since) {
  while ((uint16_t)(TCNT1 - since) < (uint16_t)MAXL_STEP_PULSE_TICKS) {
  }
}
#else
uint16_t stepTimerNow();
void stepTimerArm(uint16_t at);
void stepTimerDisarm();
inline uint8_t lockInterrupts() { return 0; }
inline void unlockInterrupts(uint8_t) {}
inline void writePinFromIsr(const OutputPin& pin, bool high) { writePin(pin, high); }
inline void stepPulseHold(uint16_t) {}
#endif
#endif  // MAXL_STEP_TIMER

}  // namespace hal
}  // namespace maxl_fw

#endif
