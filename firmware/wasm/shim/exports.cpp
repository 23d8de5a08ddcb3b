// What a firmware module exports to the simulator (firmware/WASM_ABI.md):
// the sketch's setup() and loop(), and the idle query. The receive-buffer
// exports are in src/maxl/hal/hal_wasm.cpp; static constructors run from the
// exported __wasm_call_ctors (linker flag in scripts/firmware-wasm.sh).
#include <stdint.h>

#include "MAXL.h"

void setup();
void loop();

extern "C" {
__attribute__((export_name("maxl_setup"))) void maxl_setup(void) { setup(); }
__attribute__((export_name("maxl_loop"))) void maxl_loop(void) { loop(); }
// Non-zero when nothing is due before new input: the simulator may then call
// maxl_loop rarely (see MAXL_Device::idle()).
__attribute__((export_name("maxl_idle"))) uint32_t maxl_idle(void) {
  MAXL_Device* device = MAXL_Device::instance();
  return device ? (device->idle() ? 1 : 0) : 1;
}
// µs until maxl_loop next has something to do without new input: 0 for now (loop
// at the busy period), 0xFFFFFFFF for nothing at all (see MAXL_Device::wakeAfter()).
__attribute__((export_name("maxl_wake_after"))) uint32_t maxl_wake_after(void) {
  MAXL_Device* device = MAXL_Device::instance();
  return device ? device->wakeAfter() : 0xFFFFFFFFu;
}
}
