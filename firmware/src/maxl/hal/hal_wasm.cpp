// Hardware layer in the simulator: the clock and the pins are imports, and
// received bytes arrive through the exported maxl_rx_buffer / maxl_rx_push
// pair (the simulator's stand-in for the UART receive interrupt).
#include "maxl/hal/platform.h"
#if MAXL_HAL_WASM

#include "maxl/hal/hal.h"
#include "maxl/hal/wasm_imports.h"

namespace {
const uint32_t RX_RING = 2048;      // like the UART ring, but roomier
const uint32_t RX_STAGING = 256;    // the simulator writes here, then calls push
uint8_t rxRing[RX_RING];
uint32_t rxHead = 0, rxCount = 0;
uint8_t rxStaging[RX_STAGING];
}  // namespace

extern "C" {
// Address of a 256-byte buffer in linear memory for the simulator to fill.
__attribute__((export_name("maxl_rx_buffer"))) uint8_t* maxl_rx_buffer(void) { return rxStaging; }
// Takes `length` bytes from that buffer into the receive ring; returns how many
// fitted (the rest are lost, as on a UART overrun).
__attribute__((export_name("maxl_rx_push"))) uint32_t maxl_rx_push(uint32_t length) {
  if (length > RX_STAGING) length = RX_STAGING;
  uint32_t n = 0;
  while (n < length && rxCount < RX_RING) {
    rxRing[(rxHead + rxCount) % RX_RING] = rxStaging[n++];
    rxCount++;
  }
  return n;
}
// Bytes received and not yet read by the library: the simulator keeps looping a
// device while this is non-zero (the library reads at most 32 bytes per loop).
__attribute__((export_name("maxl_rx_pending"))) uint32_t maxl_rx_pending(void) { return rxCount; }
}

namespace maxl_fw {
namespace hal {

uint32_t micros() { return maxl_micros(); }

int16_t readByte() {
  if (rxCount == 0) return -1;
  uint8_t b = rxRing[rxHead];
  rxHead = (rxHead + 1) % RX_RING;
  rxCount--;
  return b;
}

void write(const uint8_t* data, uint8_t length) { maxl_serial_write(data, length); }

void makeOutput(OutputPin& pin, uint8_t number) {
  pin.number = number;
  pin.valid = true;
  maxl_pin_mode(number, 1);
}

void writePin(const OutputPin& pin, bool high) {
  if (pin.valid) maxl_digital_write(pin.number, high ? 1 : 0);
}

void stepPulseWait() {}
void directionSetupWait() {}

}  // namespace hal
}  // namespace maxl_fw

#endif
