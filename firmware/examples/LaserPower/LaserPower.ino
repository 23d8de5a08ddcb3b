// A MAXL laser module (the paper's Listing 4): an event track sets the laser
// power per millimetre of travel, and the velocity track scales it to power
// per second as the speed changes, so the energy per mm stays constant
// through accelerations and corners.
//
// Wiring: the laser driver's PWM input on D11 (Timer 2, like GRBL's spindle).
#include <MAXL.h>

const uint8_t LASER_PIN = 11;
// Event values are power per mm relative to full power at this speed (mm/s):
// a value of 1 at 50 mm/s is full PWM; at 25 mm/s it is half.
const float FULL_POWER_SPEED = 50.0f;

MAXL_Device maxl("laserModule");

// writes a power level from 0 to 1
void writeLaserPower(float power) {
  if (power < 0.0f) power = 0.0f;
  if (power > 1.0f) power = 1.0f;
  analogWrite(LASER_PIN, (int)(power * 255.0f + 0.5f));
}

// the currently requested relative power (per mm)
float unscaledPower = 0.0f;
float lastRate = 0.0f;

void onLaserEvent(float value) {
  unscaledPower = value;
  writeLaserPower(unscaledPower * lastRate / FULL_POWER_SPEED);
}
MAXL_TrackEvent laserPowerTrack("laserPower", onLaserEvent);

// power per second must follow the speed: scale by the velocity track
void onSpeedUpdate(float rate) {
  lastRate = rate;
  writeLaserPower(unscaledPower * rate / FULL_POWER_SPEED);
}
MAXL_TrackVelocity velocityTrack("velocityReader", onSpeedUpdate);

void setup() {
  pinMode(LASER_PIN, OUTPUT);
  writeLaserPower(0.0f);
  maxl.begin(Serial);
}

void loop() { maxl.loop(); }
