// Self-test of the AVR assembly in maxl/motion/fixed_point.h: mulhi16() must
// equal the portable C form (exact by construction, and tested on the host)
// for the edge values and 200 000 pseudo-random inputs. Run in simavr by
// scripts/firmware-avr.sh; prints "MULHI OK <n>" or the first mismatch.
#include <MAXL.h>
#include <avr/sleep.h>

#include "maxl/motion/fixed_point.h"

using namespace maxl_fw;

uint32_t rngState = 2463534242UL;
uint32_t next() {  // xorshift32
  rngState ^= rngState << 13;
  rngState ^= rngState >> 17;
  rngState ^= rngState << 5;
  return rngState;
}

bool same(int32_t a, uint16_t x) {
  if (mulhi16(a, x) == mulhi16Portable(a, x)) return true;
  Serial.print("MULHI MISMATCH a=");
  Serial.print(a);
  Serial.print(" x=");
  Serial.println(x);
  return false;
}

void setup() {
  Serial.begin(1000000);
  const int32_t edges[] = {0, 1, -1, 65535L, 65536L, -65536L, 2147483647L, -2147483647L - 1, 0x7FFF0000L, -0x7FFF0001L};
  const uint16_t xs[] = {0, 1, 2, 255, 256, 32767, 32768, 65535};
  uint32_t n = 0;
  bool ok = true;
  for (uint8_t i = 0; i < sizeof(edges) / sizeof(edges[0]) && ok; i++)
    for (uint8_t j = 0; j < sizeof(xs) / sizeof(xs[0]) && ok; j++, n++) ok = same(edges[i], xs[j]);
  for (uint32_t i = 0; i < 200000UL && ok; i++, n++) ok = same((int32_t)next(), (uint16_t)next());
  if (ok) {
    Serial.print("MULHI OK ");
    Serial.println(n);
  }
  Serial.flush();
  cli();
  sleep_enable();
  sleep_cpu();
}

void loop() {}
