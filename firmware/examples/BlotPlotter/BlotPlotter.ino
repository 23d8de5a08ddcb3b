// A Blot-style pen plotter on one board (the paper's §4.3): two CoreXY
// steppers, "a" and "b", and a pen servo, all on one MAXL device. The author
// plans in x/y, transforms to the actuator tracks a = x + y and b = x − y, and
// subscribes each stepper to its track; the pen follows an event track.
//
// Wiring (Arduino CNC shield): motor A on the X socket (STEP D2, DIR D5),
// motor B on the Y socket (STEP D3, DIR D6), drivers' EN on D8 (active low),
// pen servo signal on D9.
#include <MAXL.h>

#include "servo_pulse.h"

const uint8_t ENABLE_PIN = 8;
const uint8_t PEN_PIN = 9;
const float STEPS_PER_MM = 80.0f;  // 1.8° motors at 1/16 on GT2-20 pulleys
const uint16_t PEN_UP_US = 1000;
const uint16_t PEN_DOWN_US = 1900;

MAXL_Device maxl("blot");
MAXL_Stepper motorA("a", 2, 5, STEPS_PER_MM);
MAXL_Stepper motorB("b", 3, 6, STEPS_PER_MM);
ServoPulse pen(PEN_PIN);

// 0 = pen up, 1 = pen down (anything between goes part way)
void onPen(float down) {
  if (down < 0.0f) down = 0.0f;
  if (down > 1.0f) down = 1.0f;
  pen.writeMicroseconds((uint16_t)(PEN_UP_US + down * (PEN_DOWN_US - PEN_UP_US)));
}
MAXL_TrackEvent penTrack("pen", onPen);

void setup() {
  pinMode(ENABLE_PIN, OUTPUT);
  digitalWrite(ENABLE_PIN, LOW);
  pen.begin();
  onPen(0.0f);
  maxl.begin(Serial);
}

void loop() { maxl.loop(); }
