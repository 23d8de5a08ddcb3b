// Benchmark sketch for the step-rate harness with three steppers
// (bench/firmware/simavr_steps.c with STEPPERS=3): the CncShield example's
// device (x, y, z on STEP D2/D3/D4, DIR D5/D6/D7, 80 steps/mm, all on the step
// timer; its spindle event and velocity readers, which the harness does not
// subscribe), built with its build_flags.txt, plus the harness's calibration
// and loop mark. The example's enable pin (D8) is the calibration edge here,
// and the spindle PWM (D11) is left alone: nothing else differs.
#include <MAXL.h>

#include "../bench_calibration.h"

MAXL_Device maxl("bench");
MAXL_Stepper x("x", 2, 5, 80.0f);
MAXL_Stepper y("y", 3, 6, 80.0f);
MAXL_Stepper z("z", 4, 7, 80.0f);

void onSpindle(float) {}
void onSpeed(float) {}
MAXL_TrackEvent spindleTrack("spindle", onSpindle);
MAXL_TrackVelocity velocityTrack("velocity", onSpeed);

void setup() {
  maxl.begin(Serial);
  benchCalibrate();
}

void loop() {
  benchLoopMark();
  maxl.loop();
}
