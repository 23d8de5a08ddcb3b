// Benchmark sketch for the step-rate harness (bench/firmware/simavr_steps.c):
// the Stepper example's device (one MAXL_Stepper, STEP on D2, DIR on D5),
// plus the harness's clock calibration and loop mark (../bench_calibration.h).
// The harness runs it in libsimavr, sends it real frames over the simulated
// UART and timestamps every step. Nothing else differs from the Stepper example.
#include <MAXL.h>

#include "../bench_calibration.h"

MAXL_Device maxl("bench");
MAXL_Stepper stepper("stepper", 2, 5, 80.0f);

void setup() {
  maxl.begin(Serial);
  benchCalibrate();
}

void loop() {
  benchLoopMark();
  maxl.loop();
}
