// Hardware layer for the host tests: virtual time and byte buffers.
#include "maxl/hal/platform.h"
#if MAXL_HAL_HOST

#include "maxl/hal/hal_host.h"

#include "maxl/hal/hal.h"

namespace maxl_fw {
namespace host {

namespace {
uint32_t clockUs = 0;
uint64_t tickClock = 0;  // 2 per µs
bool timerArmed = false;
uint16_t timerCompare = 0;
void (*timerIsr)() = 0;
uint8_t rxBuf[RX_CAPACITY];
size_t rxHead = 0, rxCount = 0;
uint8_t txBuf[TX_CAPACITY];
size_t txLen = 0;
bool txOver = false;
PinWrite pinBuf[PIN_LOG_CAPACITY];
size_t pinLen = 0;
bool pinOver = false;
}  // namespace

void reset() {
  clockUs = 0;
  tickClock = 0;
  timerArmed = false;
  rxHead = rxCount = 0;
  clearTx();
  clearPinLog();
}
// The count follows the clock; a jump back that would take it below 0 goes
// forward by the same amount modulo 2^33 counts (2^32 µs) instead.
void setMicros(uint32_t t) {
  int64_t d = 2 * (int64_t)(int32_t)(t - clockUs);
  if (d < 0 && (uint64_t)(-d) > tickClock) d = 2 * (int64_t)(uint32_t)(t - clockUs);
  tickClock += (uint64_t)d;
  clockUs = t;
}
uint32_t micros() { return clockUs; }
void advanceMicros(uint32_t dt) { setMicros(clockUs + dt); }

void runStepTimer(uint32_t untilUs) {
  int32_t span = (int32_t)(untilUs - clockUs);
  uint64_t end = tickClock + (span > 0 ? 2 * (uint64_t)span : 0);
  bool fired = false;  // a compare left at the count it fired at matches again 2^16 counts later, as on a chip
  while (timerArmed && timerIsr) {
    uint32_t ahead = (uint16_t)(timerCompare - (uint16_t)tickClock);
    if (ahead == 0 && fired) ahead = 65536;
    if (tickClock + ahead > end) break;
    tickClock += ahead;
    clockUs = (uint32_t)(tickClock >> 1);
    timerIsr();
    fired = true;
  }
  tickClock = end;
  clockUs = (uint32_t)(end >> 1);
  if (span > 0) clockUs = untilUs;
}
bool stepTimerArmed() { return timerArmed; }
uint16_t stepTimerCompare() { return timerCompare; }
uint64_t ticks() { return tickClock; }

size_t pushRx(const uint8_t* data, size_t length) {
  size_t n = 0;
  while (n < length && rxCount < RX_CAPACITY) {
    rxBuf[(rxHead + rxCount) % RX_CAPACITY] = data[n++];
    rxCount++;
  }
  return n;
}
size_t rxPending() { return rxCount; }

const uint8_t* tx() { return txBuf; }
size_t txLength() { return txLen; }
void clearTx() {
  txLen = 0;
  txOver = false;
}
bool txOverflowed() { return txOver; }

const PinWrite* pinLog() { return pinBuf; }
size_t pinLogLength() { return pinLen; }
bool pinLogOverflowed() { return pinOver; }
void clearPinLog() {
  pinLen = 0;
  pinOver = false;
}

}  // namespace host

namespace hal {

uint32_t micros() { return host::clockUs; }

int16_t readByte() {
  if (host::rxCount == 0) return -1;
  uint8_t b = host::rxBuf[host::rxHead];
  host::rxHead = (host::rxHead + 1) % host::RX_CAPACITY;
  host::rxCount--;
  return b;
}

void write(const uint8_t* data, uint8_t length) {
  for (uint8_t i = 0; i < length; i++) {
    if (host::txLen >= host::TX_CAPACITY) {
      host::txOver = true;
      return;
    }
    host::txBuf[host::txLen++] = data[i];
  }
}

void makeOutput(OutputPin& pin, uint8_t number) {
  pin.number = number;
  pin.valid = true;
}

void writePin(const OutputPin& pin, bool high) {
  if (!pin.valid) return;
  if (host::pinLen >= host::PIN_LOG_CAPACITY) {
    host::pinOver = true;
    return;
  }
  host::PinWrite& w = host::pinBuf[host::pinLen++];
  w.time = host::clockUs;
  w.pin = pin.number;
  w.value = high ? 1 : 0;
  w.tick = host::tickClock;
}

void stepPulseWait() {}
void directionSetupWait() {}

#if MAXL_STEP_TIMER
void stepTimerBegin(void (*isr)()) { host::timerIsr = isr; }
// The host's count is exactly 2 per µs, from 0 at µs 0.
uint16_t stepTicks(uint32_t t) { return (uint16_t)(t << 1); }
uint16_t stepTimerNow() { return (uint16_t)host::tickClock; }
void stepTimerArm(uint16_t at) {
  uint16_t now = (uint16_t)host::tickClock;
  if ((int16_t)(at - now) < (int16_t)MAXL_STEP_MIN_TICKS) at = (uint16_t)(now + MAXL_STEP_MIN_TICKS);
  host::timerCompare = at;
  host::timerArmed = true;
}
void stepTimerDisarm() { host::timerArmed = false; }
#endif

}  // namespace hal
}  // namespace maxl_fw

#endif
