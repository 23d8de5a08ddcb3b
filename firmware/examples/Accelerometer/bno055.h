// A minimal BNO055 driver over I2C (Wire): accelerometer only.
//
// The BNO055 starts in CONFIG mode. We check its chip id (register 0x00 reads
// 0xA0), set the accelerometer's range and bandwidth (page 1, ACC_Config 0x08,
// writable in CONFIG mode only), select the ACCONLY operating mode (register
// OPR_MODE 0x3D = 0x01) and read the six bytes of ACC_DATA from 0x08 (X, Y, Z,
// little-endian int16). With the default UNIT_SEL, 1 m/s² is 100 LSB, so
// mm/s² = raw × 10.
//
// ACC_Config = 0x1F: range ±16 g (bits 1:0 = 3), bandwidth 1000 Hz (bits 4:2 =
// 7), normal power (bits 7:5 = 0). The chip then makes a sample every
// SAMPLE_PERIOD_US = 1/(2 × 1000 Hz) = 500 µs, each the mean over its period,
// and holds the latest in ACC_DATA. The default (±4 g, 62.5 Hz) averages over
// 8 ms: a read could return a reading up to 12 ms old, too blurred in time to
// stamp within half a millisecond, and a belt resonance can pass 4 g.
// Every register access is a one-byte write of the register address, then a
// read (or more written bytes) from there.
#ifndef BNO055_H
#define BNO055_H

#include <Arduino.h>
#include <Wire.h>

class Bno055 {
 public:
  static const uint8_t ADDRESS = 0x28;  // ADR pin low (0x29 when high)
  static const uint8_t CHIP_ID = 0x00;
  static const uint8_t ACC_DATA_X_LSB = 0x08;
  static const uint8_t OPR_MODE = 0x3D;
  static const uint8_t MODE_CONFIG = 0x00;
  static const uint8_t MODE_ACCONLY = 0x01;
  static const uint8_t EXPECTED_CHIP_ID = 0xA0;
  static const uint8_t PAGE_ID = 0x07;
  static const uint8_t ACC_CONFIG = 0x08;  // on page 1
  static const uint8_t ACC_CONFIG_16G_1000HZ = 0x1F;
  // Time between the chip's samples at 1000 Hz bandwidth, µs.
  static const uint32_t SAMPLE_PERIOD_US = 500;

  // True if a BNO055 answered and is now measuring.
  bool begin() {
    Wire.begin();
    uint8_t id = 0;
    if (!read(CHIP_ID, &id, 1) || id != EXPECTED_CHIP_ID) return false;
    if (!write(OPR_MODE, MODE_CONFIG)) return false;
    delay(20);  // datasheet: 19 ms from any mode to CONFIG
    if (!write(PAGE_ID, 1) || !write(ACC_CONFIG, ACC_CONFIG_16G_1000HZ) || !write(PAGE_ID, 0)) return false;
    if (!write(OPR_MODE, MODE_ACCONLY)) return false;
    delay(10);  // 7 ms from CONFIG to any mode
    return true;
  }

  // Acceleration in mm/s² along the chip's X, Y, Z.
  bool readAcceleration(float* xyz) {
    uint8_t raw[6];
    if (!read(ACC_DATA_X_LSB, raw, 6)) return false;
    for (uint8_t i = 0; i < 3; i++) {
      int16_t v = (int16_t)((uint16_t)raw[2 * i] | ((uint16_t)raw[2 * i + 1] << 8));
      xyz[i] = (float)v * 10.0f;
    }
    return true;
  }

 private:
  bool write(uint8_t reg, uint8_t value) {
    Wire.beginTransmission(ADDRESS);
    Wire.write(reg);
    Wire.write(value);
    return Wire.endTransmission() == 0;
  }
  bool read(uint8_t reg, uint8_t* out, uint8_t n) {
    Wire.beginTransmission(ADDRESS);
    Wire.write(reg);
    if (Wire.endTransmission(false) != 0) return false;  // repeated start
    if (Wire.requestFrom(ADDRESS, n) != n) return false;
    for (uint8_t i = 0; i < n; i++) out[i] = (uint8_t)Wire.read();
    return true;
  }
};

#endif
