// Hardware layer for the host tests: virtual time and byte buffers.
#include "maxl/hal/platform.h"
#if MAXL_HAL_HOST

#include "maxl/hal/hal_host.h"

#include "maxl/hal/hal.h"

namespace maxl_fw {
namespace host {

namespace {
uint32_t clockUs = 0;
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
  rxHead = rxCount = 0;
  clearTx();
  clearPinLog();
}
void setMicros(uint32_t t) { clockUs = t; }
uint32_t micros() { return clockUs; }
void advanceMicros(uint32_t dt) { clockUs += dt; }

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
}

void stepPulseWait() {}
void directionSetupWait() {}

}  // namespace hal
}  // namespace maxl_fw

#endif
