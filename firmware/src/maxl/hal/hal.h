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

namespace maxl_fw {
namespace hal {

uint32_t micros();
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
void writePin(const OutputPin& pin, bool high);

// Holds a step pulse high long enough for common drivers (~2 µs on a real
// board; nothing in virtual time).
void stepPulseWait();
// Direction setup time before a step after the direction pin changed.
void directionSetupWait();

}  // namespace hal
}  // namespace maxl_fw

#endif
