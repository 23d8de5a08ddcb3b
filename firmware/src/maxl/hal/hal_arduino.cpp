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

#if MAXL_STEP_TIMER
namespace {
bool timerStarted = false;
uint16_t tickOffset = 0;  // Timer 1's count minus 2·micros()
}  // namespace

// Timer 1: normal mode (counts 0..0xFFFF and wraps), clk/8 = 2 counts per µs,
// no output compare pins (the sketch may use OC1A). Then the offset between
// its count and the device clock: wait for Timer 0 (micros(), clk/64) to
// tick, so that micros() is exact at that instant, and read Timer 1 at once.
// Both timers run from one prescaler, so on a chip the offset is exact; where
// their phases differ (simavr), the count read a few cycles after the tick is
// at most one count ahead, which only makes every step up to 0.5 µs later.
void stepTimerBegin(void (*)()) {
  if (timerStarted) return;
  timerStarted = true;
  uint8_t sreg = SREG;
  cli();
  TCCR1A = 0;
  TCCR1B = _BV(CS11);
  TIMSK1 &= (uint8_t)~(_BV(OCIE1B) | _BV(TOIE1) | _BV(ICIE1));
  uint8_t t0 = TCNT0;
  while (TCNT0 == t0) {
  }
  uint16_t count = TCNT1;
  uint32_t us = micros();
  tickOffset = (uint16_t)(count - (uint16_t)(us << 1));
  SREG = sreg;
}

uint16_t stepTicks(uint32_t t) { return (uint16_t)((uint16_t)(t << 1) + tickOffset); }
#endif

}  // namespace hal
}  // namespace maxl_fw

#endif
