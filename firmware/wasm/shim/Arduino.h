// A small Arduino-compatible API for building the firmware examples to wasm32
// for the simulator. Every call maps onto an import of firmware/WASM_ABI.md
// (src/maxl/hal/wasm_imports.h). Only what the examples and common sketches
// need is here; anything else fails to compile rather than misbehave.
//
// Time is virtual: the simulator sets the clock before each loop() and it
// does not move during one, so delay() and delayMicroseconds() return at once.
#ifndef MAXL_WASM_ARDUINO_H
#define MAXL_WASM_ARDUINO_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "maxl/hal/wasm_imports.h"

#define ARDUINO 10819
#define MAXL_WASM_SHIM 1

#define HIGH 0x1
#define LOW 0x0
#define INPUT 0x0
#define OUTPUT 0x1
#define INPUT_PULLUP 0x2

typedef bool boolean;
typedef uint8_t byte;

void pinMode(uint8_t pin, uint8_t mode);
void digitalWrite(uint8_t pin, uint8_t value);
int digitalRead(uint8_t pin);
void analogWrite(uint8_t pin, int value);
int analogRead(uint8_t pin);  // always 0: the simulator has no analogue inputs yet

unsigned long micros(void);
unsigned long millis(void);
void delay(unsigned long ms);
void delayMicroseconds(unsigned int us);
inline void noInterrupts(void) {}
inline void interrupts(void) {}

// Byte streams: the serial port is the simulated link.
class Stream {
 public:
  virtual int available() = 0;
  virtual int read() = 0;
  virtual size_t write(uint8_t b) = 0;
  virtual size_t write(const uint8_t* data, size_t length) {
    for (size_t i = 0; i < length; i++) write(data[i]);
    return length;
  }
  size_t write(const char* text) { return write((const uint8_t*)text, strlen(text)); }
  virtual void flush() {}

 protected:
  ~Stream() {}
};

// Serial: the device's link to the author. The MAXL library reads it directly
// (hal_wasm.cpp); a sketch that also reads Serial would take the library's bytes.
class HardwareSerial : public Stream {
 public:
  void begin(unsigned long) {}
  void end() {}
  int available();
  int read();
  size_t write(uint8_t b);
  size_t write(const uint8_t* data, size_t length);
  operator bool() const { return true; }
};
extern HardwareSerial Serial;

#endif
