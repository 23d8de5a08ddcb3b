// The shim's Arduino functions, each an import of firmware/WASM_ABI.md.
#include "Arduino.h"

#include "maxl/hal/hal.h"

void pinMode(uint8_t pin, uint8_t mode) { maxl_pin_mode(pin, mode); }
void digitalWrite(uint8_t pin, uint8_t value) { maxl_digital_write(pin, value ? 1 : 0); }
int digitalRead(uint8_t pin) { return maxl_digital_read(pin) ? HIGH : LOW; }
void analogWrite(uint8_t pin, int value) {
  if (value < 0) value = 0;
  if (value > 255) value = 255;
  maxl_analog_write(pin, (uint32_t)value);
}
int analogRead(uint8_t) { return 0; }

unsigned long micros(void) { return maxl_micros(); }
unsigned long millis(void) { return maxl_micros() / 1000UL; }
void delay(unsigned long) {}
void delayMicroseconds(unsigned int) {}

HardwareSerial Serial;

int HardwareSerial::available() { return 0; }  // the library owns the receive ring
int HardwareSerial::read() { return maxl_fw::hal::readByte(); }
size_t HardwareSerial::write(uint8_t b) {
  maxl_serial_write(&b, 1);
  return 1;
}
size_t HardwareSerial::write(const uint8_t* data, size_t length) {
  maxl_serial_write(data, (uint32_t)length);
  return length;
}
