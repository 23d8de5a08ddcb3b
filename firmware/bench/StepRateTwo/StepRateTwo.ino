// Benchmark sketch for the step-rate harness with two steppers
// (bench/firmware/simavr_steps.c with STEPPERS=2): BlotPlotter's CoreXY pair
// (STEP D2/DIR D5 and STEP D3/DIR D6, 80 steps/mm), both on the step timer,
// both stepping at the benchmark's rate. Calibration as StepRate's.
#include <MAXL.h>

#include "../bench_calibration.h"

MAXL_Device maxl("bench");
MAXL_Stepper motorA("a", 2, 5, 80.0f);
MAXL_Stepper motorB("b", 3, 6, 80.0f);

void setup() {
  maxl.begin(Serial);
  benchCalibrate();
}

void loop() {
  benchLoopMark();
  maxl.loop();
}
