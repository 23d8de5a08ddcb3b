// The functions a wasm32 build imports from the simulator (module "env").
// firmware/WASM_ABI.md documents each one; keep the two in step.
#ifndef MAXL_HAL_WASM_IMPORTS_H
#define MAXL_HAL_WASM_IMPORTS_H

#include <stdint.h>

#define MAXL_WASM_IMPORT(name) __attribute__((import_module("env"), import_name(#name)))

extern "C" {
// The device clock: a free-running u32 µs counter (the simulator applies the
// device's offset, drift and wrap).
MAXL_WASM_IMPORT(maxl_micros) uint32_t maxl_micros(void);
// Bytes the device sends on its serial link.
MAXL_WASM_IMPORT(maxl_serial_write) void maxl_serial_write(const uint8_t* data, uint32_t length);
// Pins: mode 0 input, 1 output, 2 input with pull-up.
MAXL_WASM_IMPORT(maxl_pin_mode) void maxl_pin_mode(uint32_t pin, uint32_t mode);
MAXL_WASM_IMPORT(maxl_digital_write) void maxl_digital_write(uint32_t pin, uint32_t value);
MAXL_WASM_IMPORT(maxl_digital_read) uint32_t maxl_digital_read(uint32_t pin);
// PWM duty 0..255, like analogWrite on an Uno.
MAXL_WASM_IMPORT(maxl_analog_write) void maxl_analog_write(uint32_t pin, uint32_t value);
// A strip of `count` RGB LEDs on `pin`: 3·count bytes, R G B per LED.
MAXL_WASM_IMPORT(maxl_led_show) void maxl_led_show(uint32_t pin, const uint8_t* rgb, uint32_t count);
// I2C: write `length` bytes to 7-bit `address`; returns 0 on ACK, else an
// Arduino Wire error code (2 address NACK, 3 data NACK).
MAXL_WASM_IMPORT(maxl_i2c_write) uint32_t maxl_i2c_write(uint32_t address, const uint8_t* data, uint32_t length);
// I2C: read `length` bytes from `address` into `data`; returns bytes read.
MAXL_WASM_IMPORT(maxl_i2c_read) uint32_t maxl_i2c_read(uint32_t address, uint8_t* data, uint32_t length);
// Hobby-servo pulse on `pin`, in µs (typically 500..2500); 0 detaches.
MAXL_WASM_IMPORT(maxl_servo_pulse) void maxl_servo_pulse(uint32_t pin, uint32_t pulseUs);
}

#endif
