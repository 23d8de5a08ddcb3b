// MAXL light painting (the paper's Figure 1 and §4.1): a strip of 8 NeoPixels
// on the tool head reads an 8-bit event track, one bit per LED. The author's
// event evaluator writes the bitmap column that matches the machine's planned
// position, so a long exposure shows letters written in light.
//
// Light per millimetre stays even through the ramps, as the paper's laser
// module keeps its power per mm (Listing 4): a velocity reader dims the strip
// in proportion to the speed. A lit LED shows
//
//   colour · min(1, v / cruise)
//
// so it leaves colour / cruise of exposure per mm of travel at every speed:
// the same while the machine accelerates as at cruise.
//
// Tracks (the author's event channels and the velocity track):
//   neopixelBitmap  bits 0..7 light LEDs 0..7 (whole numbers 0..255)
//   neopixelColour  the colour of a lit LED at cruise, 0xRRGGBB (a whole
//                   number below 2^24, exact in the wire's float)
//   neopixelCruise  the speed (mm/s) at which the strip shows that colour in
//                   full; 0 turns the dimming off (the colour shows as is)
//   velocity        the speed along the path, mm/s (MAXL_TrackVelocity)
// Until the author sets them, a lit LED is (255, 60, 10) and is not dimmed.
//
// Wiring: the strip's DIN on D6 (through ~330 Ω), 5 V and GND.
#include <MAXL.h>

#include "ws2812.h"

const uint8_t LED_PIN = 6;
const uint8_t LED_COUNT = 8;

MAXL_Device maxl("lightPainter");
Ws2812Strip<LED_PIN, LED_COUNT> strip;

uint8_t bits = 0;
uint8_t colour[3] = {255, 60, 10};
float cruise = 0.0f;  // mm/s; 0: no dimming
float speed = 0.0f;   // mm/s, from the velocity track

// What the strip shows now: the bits and one lit LED's colour.
uint8_t shownBits = 0;
uint8_t shown[3] = {0, 0, 0};

// Writes the strip only when what it shows changes (a show takes 8 × 30 µs on
// the Uno): while it is dark, speed changes cost nothing.
void refresh() {
  float scale = 1.0f;
  if (cruise > 0.0f) {
    scale = speed / cruise;
    if (scale < 0.0f) scale = -scale;
    if (scale > 1.0f) scale = 1.0f;
  }
  uint8_t lit[3];
  for (uint8_t c = 0; c < 3; c++) lit[c] = (uint8_t)((float)colour[c] * scale + 0.5f);
  if (bits == 0 && shownBits == 0) return;
  if (bits == shownBits && lit[0] == shown[0] && lit[1] == shown[1] && lit[2] == shown[2]) return;
  for (uint8_t i = 0; i < LED_COUNT; i++) {
    bool on = (bits >> i) & 1;
    strip.set(i, on ? lit[0] : 0, on ? lit[1] : 0, on ? lit[2] : 0);
  }
  strip.show();
  shownBits = bits;
  for (uint8_t c = 0; c < 3; c++) shown[c] = lit[c];
}

// A whole number from an event value, clamped to 0..max.
long wholeValue(float value, long max) {
  long v = (long)(value + 0.5f);
  if (v < 0) return 0;
  return v > max ? max : v;
}

void onBitmapColumn(float value) {
  bits = (uint8_t)wholeValue(value, 255);
  refresh();
}
MAXL_TrackEvent bitmapTrack("neopixelBitmap", onBitmapColumn);

void onColour(float value) {
  long rgb = wholeValue(value, 0xFFFFFFL);
  colour[0] = (uint8_t)(rgb >> 16);
  colour[1] = (uint8_t)(rgb >> 8);
  colour[2] = (uint8_t)rgb;
  refresh();
}
MAXL_TrackEvent colourTrack("neopixelColour", onColour);

void onCruise(float value) {
  cruise = value > 0.0f ? value : 0.0f;
  refresh();
}
MAXL_TrackEvent cruiseTrack("neopixelCruise", onCruise);

// The paper's Listing 4: a second reader follows the speed.
void onSpeedUpdate(float rate) {
  speed = rate;
  refresh();
}
MAXL_TrackVelocity velocityTrack("velocity", onSpeedUpdate);

void setup() {
  strip.begin();
  // Dark from the start: show once, whatever the strip held before.
  for (uint8_t i = 0; i < LED_COUNT; i++) strip.set(i, 0, 0, 0);
  strip.show();
  maxl.begin(Serial);
}

void loop() { maxl.loop(); }
