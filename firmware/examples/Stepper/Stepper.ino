// A MAXL stepper module (the paper's Listing 3): one stepper driver that
// follows whichever position track the author subscribes it to.
//
// Wiring (an Arduino CNC shield's X axis): STEP on D2, DIR on D5, drivers'
// EN on D8 (active low). 80 steps/mm: a 1.8° motor at 1/16 on a GT2-20 pulley.
//
// MAXL_Stepper is Listing 3 made fast: instead of a float callback that counts
// steps (MAXL_TrackPositionLinear stepperTrack("stepper", onPositionUpdate)),
// it turns the integer position into every step that is due, each loop().
#include <MAXL.h>

const uint8_t STEP_PIN = 2;
const uint8_t DIR_PIN = 5;
const uint8_t ENABLE_PIN = 8;
const float STEPS_PER_MM = 80.0f;

MAXL_Device maxl("motorOne");
MAXL_Stepper stepper("stepper", STEP_PIN, DIR_PIN, STEPS_PER_MM);

void setup() {
  pinMode(ENABLE_PIN, OUTPUT);
  digitalWrite(ENABLE_PIN, LOW);
  maxl.begin(Serial);
}

void loop() { maxl.loop(); }
