// Arduino's Wire (I2C master) over the simulator's maxl_i2c_write and
// maxl_i2c_read imports. A transmission is buffered and written at
// endTransmission(); requestFrom() reads at once. Like the AVR Wire library,
// buffers hold 32 bytes.
#ifndef MAXL_WASM_WIRE_H
#define MAXL_WASM_WIRE_H

#include "Arduino.h"

class TwoWire : public Stream {
 public:
  static const uint8_t BUFFER = 32;

  void begin() {}
  void setClock(uint32_t) {}
  void beginTransmission(uint8_t address);
  void beginTransmission(int address) { beginTransmission((uint8_t)address); }
  // 0 success, 1 data too long, 2 address NACK, 3 data NACK, 4 other.
  uint8_t endTransmission(bool sendStop = true);
  uint8_t requestFrom(uint8_t address, uint8_t quantity);
  uint8_t requestFrom(int address, int quantity) { return requestFrom((uint8_t)address, (uint8_t)quantity); }
  size_t write(uint8_t b);
  size_t write(const uint8_t* data, size_t length);
  int available();
  int read();

 private:
  uint8_t address_ = 0;
  uint8_t tx_[BUFFER];
  uint8_t txLength_ = 0;
  bool txOverflow_ = false;
  uint8_t rx_[BUFFER];
  uint8_t rxLength_ = 0;
  uint8_t rxIndex_ = 0;
};
extern TwoWire Wire;

#endif
