// Shared by the step-rate benchmark sketches (StepRate, StepRateTwo), for the
// harness bench/firmware/simavr_steps.c.
//
// benchCalibrate(): right after Timer 0 ticks, D8 goes high and the sketch
// prints "CAL <micros>" once, so the harness can turn simulator cycles into
// this device's micros() exactly. benchLoopMark(): D9 toggles once per loop(),
// so the harness can time every loop.
#ifndef MAXL_BENCH_CALIBRATION_H
#define MAXL_BENCH_CALIBRATION_H

#include <Arduino.h>

inline void benchCalibrate() {
  pinMode(8, OUTPUT);
  pinMode(9, OUTPUT);
  noInterrupts();
  uint8_t tick = TCNT0;
  while (TCNT0 == tick) {
  }
  PORTB |= _BV(0);  // D8 rises a few cycles after Timer 0 ticked
  uint32_t m = micros();
  interrupts();
  Serial.print("CAL ");
  Serial.println(m);
}

inline void benchLoopMark() { PINB = _BV(1); }  // toggle D9

#endif
