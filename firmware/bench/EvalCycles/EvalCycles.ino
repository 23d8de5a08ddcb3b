// Benchmark: CPU cycles of one position evaluation on the ATmega328P, the
// evaluation hot path of MAXL_Device::loop() (maxl_fw::Motion::tick for one
// position slot), counted with Timer 1 at prescaler 1 (one count per cycle)
// around each call, with interrupts off so no ISR lands inside.
//
// A 100 mm move from rest to rest (200 mm/s, 3000 mm/s²) is evaluated every
// 20 µs of device time, as a loop() running at 50 kHz would: 28 000
// evaluations, phase changes and 2^16-µs chunk changes included. It prints
// the mean and the largest, then the same for two slots (a CoreXY pair), and
// stops the simulator (sleep with interrupts off).
//   simavr -m atmega328p -f 16000000 EvalCycles.elf
#include <MAXL.h>
#include <avr/sleep.h>

#include "../bench_trapezoid.h"

using namespace maxl_fw;

Motion motion;

struct Stats {
  uint32_t evaluations;
  uint32_t cycles;
  uint16_t largest;
};

Stats run(uint8_t slots) {
  motion.reset();
  motion.setActiveSlots(slots);
  int32_t p0[2] = {0, 0};
  motion.setBase(p0, slots);
  int32_t delta[2] = {100L * 65536, -40L * 65536};
  uint32_t start = 1000;
  benchQueueTrapezoid(motion, 100.0f, 200.0f, 3000.0f, delta, slots, start);
  Stats s = {0, 0, 0};
  TCCR1A = 0;
  TCCR1B = 1;  // clk/1
  noInterrupts();
  for (uint32_t t = start; motion.mode() != Motion::IDLE || t == start; t += 20) {
    uint16_t before = TCNT1;
    motion.tick(t);
    uint16_t cycles = (uint16_t)(TCNT1 - before - 4);  // minus the two TCNT1 reads
    s.evaluations++;
    s.cycles += cycles;
    if (cycles > s.largest) s.largest = cycles;
  }
  interrupts();
  return s;
}

void report(const char* label, const Stats& s) {
  Serial.print(label);
  Serial.print(" evaluations=");
  Serial.print(s.evaluations);
  Serial.print(" meanCycles=");
  Serial.print((float)s.cycles / (float)s.evaluations, 1);
  Serial.print(" maxCycles=");
  Serial.println(s.largest);
}

void setup() {
  Serial.begin(1000000);
  Stats one = run(1);
  report("RESULT oneSlot", one);
  Stats two = run(2);
  report("RESULT twoSlots", two);
  Serial.println("END");
  Serial.flush();
  cli();
  sleep_enable();
  sleep_cpu();
}

void loop() {}
