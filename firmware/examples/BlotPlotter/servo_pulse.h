// One hobby servo on D9 (OC1A), its pulses made by Timer 1 in hardware: no
// library, no jitter.
//
// Timer 1 is shared with MAXL_Stepper's step interrupt (MAXL.h,
// MAXL_useTimer1()): it runs free in normal mode at 2 counts per µs, the
// steppers use OCR1B. The servo uses the other compare unit: OC1A is set
// ("set on compare match") at the start of each 20 ms frame and cleared
// ("clear on compare match") one pulse width later. Both edges are made by
// the timer at the exact count; the TIMER1_COMPA interrupt below only moves
// OCR1A on to the next edge and flips set/clear, and it has a whole pulse
// (at least 500 µs) to do so. (The earlier version ran Timer 1 in fast PWM
// mode 14 with a 20 ms TOP, which the step timer cannot share.)
//
// Without the step timer (other clocks) it keeps that fast PWM mode; in the
// simulator the pulse width goes to the maxl_servo_pulse import.
#ifndef SERVO_PULSE_H
#define SERVO_PULSE_H

#include <Arduino.h>
#include <MAXL.h>

#if defined(__wasm__)
#include "maxl/hal/wasm_imports.h"
#endif

#if defined(__AVR_ATmega328P__) || defined(__AVR_ATmega168__)
#if MAXL_STEP_TIMER
#define SERVO_PULSE_SHARED_TIMER1 1
#else
#define SERVO_PULSE_PWM_TIMER1 1
#endif
#endif

class ServoPulse {
 public:
  static const uint16_t FRAME_US = 20000;

  // `pin`: 9 (OC1A). (Pin 10, OC1B, belongs to the steppers' timer.)
  explicit ServoPulse(uint8_t pin) : pin_(pin) {}

  void begin() {
#if SERVO_PULSE_SHARED_TIMER1
    pinMode(9, OUTPUT);
    MAXL_useTimer1();
    uint8_t sreg = SREG;
    cli();
    OCR1A = (uint16_t)(TCNT1 + 200);                    // the first frame starts in 100 µs
    TCCR1A |= (uint8_t)(_BV(COM1A1) | _BV(COM1A0));     // set OC1A on match
    TIFR1 = _BV(OCF1A);
    TIMSK1 |= _BV(OCIE1A);
    SREG = sreg;
#elif SERVO_PULSE_PWM_TIMER1
    pinMode(9, OUTPUT);
    TCCR1A = (uint8_t)((1 << WGM11) | (1 << COM1A1));
    TCCR1B = (uint8_t)((1 << WGM13) | (1 << WGM12) | (1 << CS11));  // mode 14, clk/8
    ICR1 = (uint16_t)(F_CPU / 8 / 50 - 1);
#endif
  }

  // Pulse width in µs, clamped to 500..2500.
  void writeMicroseconds(uint16_t us) {
    if (us < 500) us = 500;
    if (us > 2500) us = 2500;
#if SERVO_PULSE_SHARED_TIMER1
    uint8_t sreg = SREG;
    cli();
    widthCounts = (uint16_t)(us * 2);
    SREG = sreg;
#elif SERVO_PULSE_PWM_TIMER1
    OCR1A = (uint16_t)(us * (uint16_t)(F_CPU / 8000000UL) - 1);
#elif defined(__wasm__)
    maxl_servo_pulse(pin_, us);
#endif
  }

  // The pulse width in Timer 1 counts, for the interrupt.
  static volatile uint16_t widthCounts;

 private:
  uint8_t pin_;
};

volatile uint16_t ServoPulse::widthCounts = 3000;  // 1.5 ms until told

#if SERVO_PULSE_SHARED_TIMER1
// OC1A has just been set (a pulse starts) or cleared (it ends): schedule the
// other edge. COM1A0 tells which: 1 = "set on match" was armed.
ISR(TIMER1_COMPA_vect) {
  uint16_t width = ServoPulse::widthCounts;
  if (TCCR1A & _BV(COM1A0)) {
    TCCR1A &= (uint8_t)~_BV(COM1A0);  // next match clears
    OCR1A += width;
  } else {
    TCCR1A |= _BV(COM1A0);  // next match sets: the next frame
    OCR1A += (uint16_t)(2u * ServoPulse::FRAME_US - width);
  }
}
#endif

#endif
