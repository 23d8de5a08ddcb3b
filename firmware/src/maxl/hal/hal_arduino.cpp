// Hardware layer on a real board, through the Arduino core.
#include "maxl/hal/platform.h"
#if MAXL_HAL_ARDUINO

#include <Arduino.h>

#include "maxl/hal/hal.h"

namespace maxl_fw {
namespace hal {

namespace {
Stream* link = 0;
}

#if !MAXL_INLINE_MICROS
uint32_t micros() { return ::micros(); }
#endif

int16_t readByte() {
  if (!link) return -1;
  return (int16_t)link->read();  // -1 when the receive buffer is empty
}

void write(const uint8_t* data, uint8_t length) {
  if (link) link->write(data, length);
}

void attach(Stream& stream) { link = &stream; }

void makeOutput(OutputPin& pin, uint8_t number) {
  pin.number = number;
  pin.valid = true;
  pinMode(number, OUTPUT);
#if defined(__AVR__)
  uint8_t port = digitalPinToPort(number);
  if (port == NOT_A_PIN) {
    pin.valid = false;
    return;
  }
  pin.port = portOutputRegister(port);
  pin.mask = digitalPinToBitMask(number);
#endif
}

#if !defined(__AVR__)
void writePin(const OutputPin& pin, bool high) {
  if (pin.valid) digitalWrite(pin.number, high ? HIGH : LOW);
}
#endif

void stepPulseWait() { delayMicroseconds(2); }
void directionSetupWait() { delayMicroseconds(1); }

}  // namespace hal
}  // namespace maxl_fw

#endif
