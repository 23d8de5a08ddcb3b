// MAXL light painting (the paper's Figure 1 and §4.1): a strip of 8 NeoPixels
// on the tool head reads an 8-bit event track, one bit per LED. The author's
// event evaluator writes the bitmap column that matches the machine's planned
// position, so a long exposure shows letters written in light.
//
// Wiring: the strip's DIN on D6 (through ~330 Ω), 5 V and GND.
#include <MAXL.h>

#include "ws2812.h"

const uint8_t LED_PIN = 6;
const uint8_t LED_COUNT = 8;
// colour of a lit pixel
const uint8_t RED = 255, GREEN = 60, BLUE = 10;

MAXL_Device maxl("lightPainter");
Ws2812Strip<LED_PIN, LED_COUNT> strip;

// value: bits 0..7 light LEDs 0..7 (the value is a float on the wire; the
// track carries whole numbers 0..255)
void onBitmapColumn(float value) {
  long bits = (long)(value + 0.5f);
  if (bits < 0) bits = 0;
  if (bits > 255) bits = 255;
  for (uint8_t i = 0; i < LED_COUNT; i++) {
    bool on = (bits >> i) & 1;
    strip.set(i, on ? RED : 0, on ? GREEN : 0, on ? BLUE : 0);
  }
  strip.show();
}
MAXL_TrackEvent bitmapTrack("neopixelBitmap", onBitmapColumn);

void setup() {
  strip.begin();
  onBitmapColumn(0);
  maxl.begin(Serial);
}

void loop() { maxl.loop(); }
