// A three-axis machine on an Arduino Uno with a CNC shield (the board GRBL
// drives): x, y and z steppers on the shield's sockets, all three stepping
// from one timer interrupt, and a spindle or laser whose PWM power follows
// the paper's Listing 4: an event track sets the power per millimetre of
// travel, the velocity track scales it to power per second, so the energy
// per mm stays the same through accelerations and corners.
//
// Wiring (CNC shield v3): X socket STEP D2 / DIR D5, Y socket STEP D3 / DIR
// D6, Z socket STEP D4 / DIR D7, the drivers' EN on D8 (active low); the
// spindle or laser driver's PWM input on D11 (Timer 2, as GRBL's spindle PWM;
// Timer 1 is the library's step timer).
//
// build_flags.txt sets three position slots (the Uno's default is two) and
// leaves out what this sketch does not use (firmware/README.md).
#include <MAXL.h>

const uint8_t ENABLE_PIN = 8;
const uint8_t SPINDLE_PIN = 11;
const float STEPS_PER_MM = 80.0f;  // 1.8° motors at 1/16 on GT2-20 pulleys; set each axis to your machine's
// Event values are power per mm relative to full power at this speed (mm/s):
// a value of 1 at 50 mm/s is full PWM; at 25 mm/s it is half.
const float FULL_POWER_SPEED = 50.0f;

MAXL_Device maxl("cncShield");
MAXL_Stepper x("x", 2, 5, STEPS_PER_MM);
MAXL_Stepper y("y", 3, 6, STEPS_PER_MM);
MAXL_Stepper z("z", 4, 7, STEPS_PER_MM);

float powerPerMm = 0.0f;  // the event track's value
float speed = 0.0f;       // the velocity track's, mm/s

// PWM duty 0..255 on D11. On the Uno straight to Timer 2 (which Arduino's
// init() already runs in 8-bit phase-correct PWM at 490 Hz): OC2A on for a
// duty inside 1..254, the pin held low or high otherwise, as analogWrite()
// does for D11, without analogWrite()'s code for every pin (flash is short).
void writeDuty(uint8_t duty) {
#if defined(__AVR__)
  if (duty == 0 || duty == 255) {
    TCCR2A &= (uint8_t)~_BV(COM2A1);
    if (duty) PORTB |= _BV(3); else PORTB &= (uint8_t)~_BV(3);  // D11 is PB3
  } else {
    OCR2A = duty;
    TCCR2A |= _BV(COM2A1);
  }
#else
  analogWrite(SPINDLE_PIN, duty);
#endif
}

// power 0..1 = power per mm × speed / FULL_POWER_SPEED, as PWM: the duty is
// power·255, rounded, 0 below (or NaN) and 255 from full power on.
void writeSpindle() {
  float duty = powerPerMm * speed * (255.0f / FULL_POWER_SPEED);
  uint8_t d = 0;
  if (duty >= 254.5f) d = 255;
  else if (duty > 0.0f) d = (uint8_t)(duty + 0.5f);
  writeDuty(d);
}
void onSpindle(float value) {
  powerPerMm = value;
  writeSpindle();
}
void onSpeed(float mmPerS) {
  speed = mmPerS;
  writeSpindle();
}
MAXL_TrackEvent spindleTrack("spindle", onSpindle);
MAXL_TrackVelocity velocityTrack("velocity", onSpeed);

void setup() {
#if defined(__AVR__)
  // D8 (enable, PB0) and D11 (spindle, PB3) outputs, low: the drivers on, the
  // spindle off. Straight to port B, as writeDuty does: digitalWrite()'s
  // timer lookup alone is ~100 bytes of flash.
  DDRB |= _BV(0) | _BV(3);
  PORTB &= (uint8_t)~(_BV(0) | _BV(3));
#else
  pinMode(ENABLE_PIN, OUTPUT);
  digitalWrite(ENABLE_PIN, LOW);
  pinMode(SPINDLE_PIN, OUTPUT);
#endif
  writeSpindle();
  maxl.begin(Serial);
}

void loop() { maxl.loop(); }
