// A probe firmware for the simulator's own tests (not a MAXL reader): it speaks
// the same wasm ABI as the real firmware (firmware/src/maxl/hal/wasm_imports.h
// and hal_wasm.cpp's rx buffer), with a tiny command set, so the device host can
// be tested without the MAXL library. Build: ./build-probe.sh (clang, wasm32).
//
// Each received byte is a command, answered on serial with 5 bytes: the
// command byte, then micros() at that loop, u32 little-endian.
//   'b'  stay busy for the next 10 loops (idle() is 0 meanwhile), writing pin 13 in each
//   's'  one step: DIR (pin 5) high, STEP (pin 2) high then low
//   'i'  I2C: write register 0 to 0x28, read 1 byte; answer it instead of micros' low byte
//   'l'  show 2 LEDs on pin 6: (1,2,3) (4,5,6)
//   'p'  servo pulse 1500 µs on pin 9
//   'n'  answer the probe's name (a string in its data) instead: [n, the name's bytes, NUL]
//   'w'  busy-wait until micros() has moved 5000 µs (like delay(5)), then step
//   't'  trap (unreachable)
//   anything else: echo only
#include <stdint.h>
#define IMPORT(name) __attribute__((import_module("env"), import_name(#name)))
#define EXPORT(name) __attribute__((export_name(#name)))

IMPORT(maxl_micros) uint32_t maxl_micros(void);
IMPORT(maxl_serial_write) void maxl_serial_write(const uint8_t* data, uint32_t length);
IMPORT(maxl_pin_mode) void maxl_pin_mode(uint32_t pin, uint32_t mode);
IMPORT(maxl_digital_write) void maxl_digital_write(uint32_t pin, uint32_t value);
IMPORT(maxl_led_show) void maxl_led_show(uint32_t pin, const uint8_t* rgb, uint32_t count);
IMPORT(maxl_i2c_write) uint32_t maxl_i2c_write(uint32_t address, const uint8_t* data, uint32_t length);
IMPORT(maxl_i2c_read) uint32_t maxl_i2c_read(uint32_t address, uint8_t* data, uint32_t length);
IMPORT(maxl_servo_pulse) void maxl_servo_pulse(uint32_t pin, uint32_t pulseUs);

static const char* volatile name = "probeDevice";
static uint8_t staging[256];
static uint8_t ring[2048];
static uint32_t head, count;
static uint32_t busyLoops, loops, setups;

EXPORT(maxl_rx_buffer) uint8_t* rx_buffer(void) { return staging; }
EXPORT(maxl_rx_push) uint32_t rx_push(uint32_t length) {
  uint32_t n = 0;
  while (n < length && count < sizeof ring) ring[(head + count++) % sizeof ring] = staging[n++];
  return n;
}
EXPORT(maxl_setup) void setup(void) {
  setups++;
  maxl_pin_mode(2, 1);
  maxl_pin_mode(5, 1);
}
EXPORT(maxl_idle) uint32_t idle(void) { return busyLoops == 0; }
EXPORT(probe_loops) uint32_t probe_loops(void) { return loops; }
EXPORT(probe_setups) uint32_t probe_setups(void) { return setups; }

EXPORT(maxl_loop) void loop(void) {
  loops++;
  if (busyLoops > 0) {
    busyLoops--;
    maxl_digital_write(13, loops & 1);  // a trace of each busy loop
  }
  while (count > 0) {
    uint8_t c = ring[head];
    head = (head + 1) % sizeof ring;
    count--;
    uint32_t now = maxl_micros();
    uint8_t answer[5] = {c, (uint8_t)now, (uint8_t)(now >> 8), (uint8_t)(now >> 16), (uint8_t)(now >> 24)};
    if (c == 'b') busyLoops = 10;
    if (c == 's') {
      maxl_digital_write(5, 1);
      maxl_digital_write(2, 1);
      maxl_digital_write(2, 0);
    }
    if (c == 'i') {
      uint8_t reg = 0, value = 0;
      maxl_i2c_write(0x28, &reg, 1);
      maxl_i2c_read(0x28, &value, 1);
      answer[1] = value;
    }
    if (c == 'l') {
      static const uint8_t rgb[6] = {1, 2, 3, 4, 5, 6};
      maxl_led_show(6, rgb, 2);
    }
    if (c == 'p') maxl_servo_pulse(9, 1500);
    if (c == 'w') {
      uint32_t start = maxl_micros();
      while ((uint32_t)(maxl_micros() - start) < 5000) {
      }
      maxl_digital_write(2, 1);
      maxl_digital_write(2, 0);
    }
    if (c == 't') __builtin_trap();
    if (c == 'n') {
      uint32_t n = 0;
      while (name[n]) n++;
      maxl_serial_write(&c, 1);
      maxl_serial_write((const uint8_t*)name, n + 1);
      continue;
    }
    maxl_serial_write(answer, 5);
  }
}
