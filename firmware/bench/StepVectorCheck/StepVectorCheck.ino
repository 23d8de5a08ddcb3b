// Self-test of the step vector (TIMER1_COMPB, AVR assembly in
// maxl/readers/step_timer.cpp): it must do exactly what the C form,
// serviceAll (StepTimer::interrupt(), the form the host tests run), does to
// the same channels. Two twin sets of three channels, set A on PORTB (STEP
// D8–D10, or D8, D9 and D7 on PORTD every other case; DIR D11–D13) for the vector and set B on PORTC (STEP A0–A2, DIR
// A3–A5) for the C form, start from the same random state: 1 to 3
// channels, rings of 0 to MAXL_STEP_RING runs of 1 to 3 steps (so that runs
// end and the next one is promoted often) in random directions, ticks due or
// not around the count, random invert and DIR levels. Each case then runs up
// to 6 interrupts, the count moving on by 0–1 000 ticks between them, and
// after each compares every channel's bytes (runs, head, ring count, DIR
// state), the STEP pins (low after the pulse), the DIR pins, whether the
// compare is on (OCIE1B) and the compare (OCR1B), the same in both forms and as arm()'s rule gives.
//
// Timer 1 counts edges on T1 (D5), where none come, so both forms read the
// same count (the C form is
// StepTimer::interruptWithoutHold(), serviceAll without the pulse hold, which
// would wait for the count forever); interrupts stay off (nothing else is
// enabled when the vector's reti sets I). Run in simavr by scripts/firmware-avr.sh;
// prints "VECTOR OK <interrupts> dir <direction changes>" or the first
// mismatch.
#include <MAXL.h>
#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/sleep.h>

#include "maxl/readers/step_timer.h"

using namespace maxl_fw;

uint32_t rngState = 2463534242UL;
uint32_t next() {  // xorshift32
  rngState ^= rngState << 13;
  rngState ^= rngState >> 17;
  rngState ^= rngState << 5;
  return rngState;
}

StepChannel setA[3], setB[3];
const uint8_t PINS = 0x3F;  // STEP bits 0..2, DIR bits 3..5 of PORTB (A) and PORTC (B)

// The bytes of a channel the interrupt may change or reads: the runs and the
// ring's state (not the pins' descriptions, which differ between the sets).
// An idle channel's current_ is only its count (no steps): its time is left
// over from the spent run (the C form advanced it once more, the vector not).
bool sameChannel(const StepChannel& a, const StepChannel& b) {
  if (a.head_ != b.head_ || a.count_ != b.count_ || a.backward_ != b.backward_ || a.invert != b.invert ||
      a.current_.count != b.current_.count)
    return false;
  if (a.count_ && memcmp(&a.current_, &b.current_, sizeof(StepRun))) return false;
  return !memcmp(a.queued_, b.queued_, sizeof(a.queued_));
}

void randomRun(StepRun& r, uint16_t now) {
  // the next step 0..±1 500 ticks from the count (a due one is up to 1 500
  // late), every 0 to 1 023 ticks; Q16.16 with a random fraction
  r.next = ((uint32_t)(uint16_t)(now + (int16_t)(next() % 3001) - 1500) << 16) | (next() & 0xFFFF);
  r.interval = next() & 0x03FFFFFFUL;
  r.count = (uint8_t)(1 + next() % 3) | (next() & 1 ? StepChannel::BACKWARD : 0);
}

void randomChannel(StepChannel& c, uint16_t now) {
  c.count_ = (uint8_t)(next() % (MAXL_STEP_RING + 1));
  c.head_ = (uint8_t)(next() % StepChannel::QUEUED);
  for (uint8_t i = 0; i < StepChannel::QUEUED; i++) randomRun(c.queued_[i], now);
  randomRun(c.current_, now);
  if (!c.count_) c.current_.count &= StepChannel::BACKWARD;  // idle: no steps in current_
  c.invert = next() & 1;
  // DIR follows the run going out (push and promote keep it so); idle, any state
  static const uint8_t idleStates[3] = {0, StepChannel::BACKWARD, StepChannel::UNKNOWN};
  c.backward_ = c.count_ ? (uint8_t)(c.current_.count & StepChannel::BACKWARD) : idleStates[next() % 3];
}

void freezeAt(uint16_t now) {
  TCNT1 = now;
  TIFR1 = _BV(OCF1B);
  TIMSK1 = _BV(OCIE1B);
}

// The compare both forms must set (arm()): the earliest next step of every
// channel with a run, or MAXL_STEP_MIN_TICKS from the count if that is later.
uint16_t expectedCompare(uint8_t channels, uint16_t now) {
  int16_t earliest = 0x7FFF;
  for (uint8_t i = 0; i < channels; i++) {
    uint16_t at;
    if (setB[i].nextDue(at) && (int16_t)(at - now) < earliest) earliest = (int16_t)(at - now);
  }
  return (uint16_t)(now + (earliest < MAXL_STEP_MIN_TICKS ? MAXL_STEP_MIN_TICKS : earliest));
}

void callVector() {
  __asm__ __volatile__("call __vector_12\n\tcli" ::: "memory");
}

uint8_t stepPins(volatile uint8_t& port) { return port & 0x07; }

void report(uint32_t n, uint8_t i, const char* what) {
  Serial.print("VECTOR MISMATCH interrupt ");
  Serial.print(n);
  Serial.print(" channel ");
  Serial.print(i);
  Serial.print(": ");
  Serial.println(what);
}

void setup() {
  Serial.begin(1000000);
  Serial.flush();
  cli();
  TIMSK0 = 0;  // no millis(): nothing may interrupt once reti sets I
  TCCR1A = 0;
  TCCR1B = _BV(CS12) | _BV(CS11);  // counting edges on T1 (D5), where none come: the count stays put
  for (uint8_t i = 0; i < 3; i++) {
    hal::makeOutput(setA[i].stepPin, (uint8_t)(8 + i));
    hal::makeOutput(setA[i].dirPin, (uint8_t)(11 + i));
    hal::makeOutput(setB[i].stepPin, (uint8_t)(A0 + i));
    hal::makeOutput(setB[i].dirPin, (uint8_t)(A3 + i));
  }
  uint32_t interrupts = 0, dirChanges = 0;
  bool ok = true;
  for (uint16_t k = 0; k < 2500 && ok; k++) {
    uint16_t now = (uint16_t)next();
    uint8_t channels = (uint8_t)(1 + next() % 3);
    // every other case, set A's third STEP pin on D7 (PORTD): STEP pins on two
    // ports, which the vector lowers one channel at a time
    hal::makeOutput(setA[2].stepPin, (uint8_t)(k & 1 ? 7 : 10));
    for (uint8_t i = 0; i < channels; i++) {
      randomChannel(setA[i], now);
      memcpy(&setB[i].current_, &setA[i].current_, sizeof(StepRun));
      memcpy(setB[i].queued_, setA[i].queued_, sizeof(setA[i].queued_));
      setB[i].head_ = setA[i].head_;
      setB[i].count_ = setA[i].count_;
      setB[i].backward_ = setA[i].backward_;
      setB[i].invert = setA[i].invert;
    }
    uint8_t dir = (uint8_t)(next() & 0x38);
    PORTB = (uint8_t)((PORTB & ~PINS) | dir);
    PORTC = (uint8_t)((PORTC & ~PINS) | dir);
    for (uint8_t call = 0; call < 6 && ok; call++, interrupts++) {
      uint8_t dirBefore = PORTB & 0x38;
      for (uint8_t i = 0; i < channels; i++) StepTimer::channels_[i] = &setA[i];
      StepTimer::count_ = channels;
      freezeAt(now);
      callVector();
      uint16_t compareA = OCR1B;
      uint8_t onA = TIMSK1 & _BV(OCIE1B);
      for (uint8_t i = 0; i < channels; i++) StepTimer::channels_[i] = &setB[i];
      freezeAt(now);
      StepTimer::interruptWithoutHold();
      uint16_t compareB = OCR1B;
      uint8_t onB = TIMSK1 & _BV(OCIE1B);
      for (uint8_t i = 0; i < channels && ok; i++)
        if (!sameChannel(setA[i], setB[i])) {
          report(interrupts, i, "channel state");
          ok = false;
        }
      if (ok && (stepPins(PORTB) || stepPins(PORTC) || (PORTD & 0x80))) {
        report(interrupts, 0, "a STEP pin left high");
        ok = false;
      }
      if (ok && (PORTB & 0x38) != (PORTC & 0x38)) {
        report(interrupts, 0, "DIR pins");
        ok = false;
      }
      if (ok && onA != onB) {
        report(interrupts, 0, "compare on/off");
        ok = false;
      }
      if (ok && onA && (compareA != compareB || compareA != expectedCompare(channels, now))) {
        report(interrupts, 0, "compare");
        ok = false;
      }
      if ((PORTB & 0x38) != dirBefore) dirChanges++;
      now = (uint16_t)(now + next() % 1001);
    }
  }
  TIMSK1 = 0;
  sei();
  if (ok) {
    Serial.print("VECTOR OK ");
    Serial.print(interrupts);
    Serial.print(" dir ");
    Serial.println(dirChanges);
  }
  Serial.flush();
  cli();
  sleep_enable();
  sleep_cpu();
}

void loop() {}
