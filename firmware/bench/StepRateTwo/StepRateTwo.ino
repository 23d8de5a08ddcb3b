// Benchmark sketch for the step-rate harness with two steppers
// (bench/firmware/simavr_steps.c with STEPPERS=2): BlotPlotter's CoreXY pair
// (STEP D2/DIR D5 and STEP D3/DIR D6, 80 steps/mm), both on the step timer,
// both stepping at the benchmark's rate. The calibration is StepRate's.
#include <MAXL.h>

MAXL_Device maxl("bench");
MAXL_Stepper motorA("a", 2, 5, 80.0f);
MAXL_Stepper motorB("b", 3, 6, 80.0f);

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
