// Benchmark sketch for the step-rate harness (bench/firmware/simavr_steps.c):
// the Stepper example's device (one MAXL_Stepper, STEP on D2, DIR on D5),
// plus a clock calibration for the harness, which runs it in libsimavr,
// sends it real frames over the simulated UART and timestamps every step.
//
// Calibration: right after Timer 0 ticks, D8 goes high and the sketch prints
// "CAL <micros>" once, so the harness can turn simulator cycles into this
// device's micros() exactly. Nothing else differs from the Stepper example.
#include <MAXL.h>

MAXL_Device maxl("bench");
MAXL_Stepper stepper("stepper", 2, 5, 80.0f);

void setup() {
  maxl.begin(Serial);
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

void loop() {
  PINB = _BV(1);  // toggle D9
  maxl.loop();
}
