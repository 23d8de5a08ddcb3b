// Benchmark: CPU cycles of one position evaluation on the ATmega328P, the
// evaluation hot path of MAXL_Device::loop() (maxl_fw::Motion::tick for the
// subscribed position slots), counted with Timer 1 at prescaler 1 (one count
// per cycle) around each call, with interrupts off so no ISR lands inside.
//
// Evaluated every 20 µs of device time, as a loop() running at 50 kHz would:
//   oneSlot, twoSlots  a 100 mm move from rest to rest (200 mm/s, 3000 mm/s²):
//                      28 000 evaluations, phase and 2^16-µs chunk changes
//                      included; one slot, then a CoreXY pair
//   spiral             300 mm of an Archimedean spiral in 0.5 mm pieces, two
//                      slots (bench_spiral.h): a segment ends every 3.3 ms at
//                      150 mm/s, with ramps from rest, to a corner and to rest
// Each prints the count, the mean, the 99th percentile and the largest. The
// percentile comes from a histogram of 8-cycle bins, so it is the upper edge
// of its bin (at most 7 cycles above the exact one); the mean and the largest
// are exact. Then the sketch stops the simulator (sleep, interrupts off).
//   simavr -m atmega328p -f 16000000 EvalCycles.elf
#include <MAXL.h>
#include <avr/sleep.h>

#include "../bench_spiral.h"
#include "../bench_trapezoid.h"

using namespace maxl_fw;

Motion motion;

const uint8_t BIN_CYCLES = 8;
const uint16_t BINS = 256;  // up to 2 048 cycles; larger ones in the last bin

struct Stats {
  uint32_t evaluations;
  uint32_t cycles;
  uint16_t largest;
  uint16_t bins[BINS];  // saturating counts; only the top 1 % needs to be exact

  void clear() {
    evaluations = cycles = 0;
    largest = 0;
    for (uint16_t i = 0; i < BINS; i++) bins[i] = 0;
  }
  void add(uint16_t c) {
    evaluations++;
    cycles += c;
    if (c > largest) largest = c;
    uint16_t bin = c / BIN_CYCLES;
    if (bin >= BINS) bin = BINS - 1;
    if (bins[bin] != 0xFFFF) bins[bin]++;
  }
  // Smallest bin edge with at most 1 % of the evaluations above it.
  uint16_t p99() const {
    uint32_t allowed = evaluations / 100;
    uint32_t above = 0;
    for (uint16_t i = BINS; i-- > 0;) {
      above += bins[i];
      if (above > allowed) return i + 1 >= BINS ? largest : (uint16_t)((i + 1) * BIN_CYCLES - 1);
    }
    return 0;
  }
};

Stats stats;

// One timed call of motion.tick(t).
inline void timedTick(uint32_t t) {
  uint16_t before = TCNT1;
  motion.tick(t);
  stats.add((uint16_t)(TCNT1 - before - 4));  // minus the two TCNT1 reads
}

void startTimer() {
  TCCR1A = 0;
  TCCR1B = 1;  // clk/1
}

void runTrapezoid(uint8_t slots) {
  stats.clear();
  motion.reset();
  motion.setActiveSlots(slots);
  int32_t p0[2] = {0, 0};
  motion.setBase(p0, slots);
  int32_t delta[2] = {100L * 65536, -40L * 65536};
  uint32_t start = 1000;
  benchQueueTrapezoid(motion, 100.0f, 200.0f, 3000.0f, delta, slots, start);
  startTimer();
  noInterrupts();
  for (uint32_t t = start; motion.mode() != Motion::IDLE || t == start; t += 20) timedTick(t);
  interrupts();
}

bench_spiral::Spiral spiral;

void runSpiral() {
  stats.clear();
  uint32_t start = 1000;
  spiral.begin(motion, start);
  spiral.refill(motion);
  startTimer();
  noInterrupts();
  for (uint32_t t = start; motion.mode() != Motion::IDLE || t == start; t += 20) {
    timedTick(t);
    spiral.refill(motion);  // outside the count: the TIMING handler's work
  }
  interrupts();
}

void report(const char* label) {
  Serial.print(label);
  Serial.print(" evaluations=");
  Serial.print(stats.evaluations);
  Serial.print(" meanCycles=");
  Serial.print((float)stats.cycles / (float)stats.evaluations, 1);
  Serial.print(" p99Cycles=");
  Serial.print(stats.p99());
  Serial.print(" maxCycles=");
  Serial.println(stats.largest);
}

void setup() {
  Serial.begin(1000000);
  runTrapezoid(1);
  report("RESULT oneSlot");
  runTrapezoid(2);
  report("RESULT twoSlots");
  runSpiral();
  report("RESULT spiral");
  Serial.println("END");
  Serial.flush();
  cli();
  sleep_enable();
  sleep_cpu();
}

void loop() {}
