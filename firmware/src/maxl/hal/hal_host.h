// Controls of the host hardware layer, for the GoogleTest suite: a virtual
// clock the test sets, a receive buffer the test fills, a transmit buffer it
// reads, and a log of pin writes with the virtual time of each.
#ifndef MAXL_HAL_HAL_HOST_H
#define MAXL_HAL_HAL_HOST_H

#include <stddef.h>
#include <stdint.h>

namespace maxl_fw {
namespace host {

const size_t RX_CAPACITY = 8192;
const size_t TX_CAPACITY = 65536;
const size_t PIN_LOG_CAPACITY = 1 << 20;

struct PinWrite {
  uint32_t time;
  uint8_t pin;
  uint8_t value;
  uint64_t tick;  // 2 per µs: the step timer writes pins between µs
};

void reset();                      // clock 0, buffers and log empty
void setMicros(uint32_t t);
uint32_t micros();
void advanceMicros(uint32_t dt);

size_t pushRx(const uint8_t* data, size_t length);  // bytes accepted
size_t rxPending();

const uint8_t* tx();                // bytes the device wrote since clearTx()
size_t txLength();
void clearTx();
bool txOverflowed();

const PinWrite* pinLog();
size_t pinLogLength();
bool pinLogOverflowed();
void clearPinLog();

// The virtual step timer (hal.h, MAXL_STEP_TIMER): a count of 2 per µs of the
// virtual clock. runStepTimer() runs every compare due up to `untilUs` (in
// order, with the clock at the compare's count: a step is logged at its
// exact half µs), then sets the clock to `untilUs`.
void runStepTimer(uint32_t untilUs);
bool stepTimerArmed();
uint16_t stepTimerCompare();
uint64_t ticks();  // the count, not wrapped

}  // namespace host
}  // namespace maxl_fw

#endif
