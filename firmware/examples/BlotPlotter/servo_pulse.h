// One hobby servo on D9 or D10, driven by Timer 1 in hardware: no library,
// no interrupt, no CPU time once set (the Servo library would use Timer 1's
// interrupt for up to 12 servos; one pen needs none of that).
//
// Timer 1 runs at 2 MHz (16 MHz / 8) in fast PWM mode 14 with TOP = ICR1 =
// 39 999, so it wraps every 20 ms (50 Hz), and OC1A (D9) or OC1B (D10) stays
// high for OCR1x + 1 counts of 0.5 µs: the pulse width.
//
// In the simulator the pulse width goes to the maxl_servo_pulse import.
#ifndef SERVO_PULSE_H
#define SERVO_PULSE_H

#include <Arduino.h>

#if defined(__wasm__)
#include "maxl/hal/wasm_imports.h"
#endif

class ServoPulse {
 public:
  explicit ServoPulse(uint8_t pin) : pin_(pin) {}

  void begin() {
#if defined(__AVR_ATmega328P__) || defined(__AVR_ATmega168__)
    pinMode(pin_, OUTPUT);
    TCCR1A = (uint8_t)((1 << WGM11) | (pin_ == 10 ? (1 << COM1B1) : (1 << COM1A1)));
    TCCR1B = (uint8_t)((1 << WGM13) | (1 << WGM12) | (1 << CS11));  // mode 14, clk/8
    ICR1 = 39999;
#endif
  }

  // Pulse width in µs, clamped to 500..2500.
  void writeMicroseconds(uint16_t us) {
    if (us < 500) us = 500;
    if (us > 2500) us = 2500;
#if defined(__AVR_ATmega328P__) || defined(__AVR_ATmega168__)
    uint16_t counts = (uint16_t)(us * 2 - 1);
    if (pin_ == 10)
      OCR1B = counts;
    else
      OCR1A = counts;
#elif defined(__wasm__)
    maxl_servo_pulse(pin_, us);
#endif
  }

 private:
  uint8_t pin_;
};

#endif
