#include "Wire.h"

TwoWire Wire;

void TwoWire::beginTransmission(uint8_t address) {
  address_ = address;
  txLength_ = 0;
  txOverflow_ = false;
}

uint8_t TwoWire::endTransmission(bool) {
  if (txOverflow_) return 1;
  uint32_t status = maxl_i2c_write(address_, tx_, txLength_);
  txLength_ = 0;
  return status > 4 ? 4 : (uint8_t)status;
}

uint8_t TwoWire::requestFrom(uint8_t address, uint8_t quantity) {
  if (quantity > BUFFER) quantity = BUFFER;
  uint32_t n = maxl_i2c_read(address, rx_, quantity);
  rxLength_ = n > quantity ? quantity : (uint8_t)n;
  rxIndex_ = 0;
  return rxLength_;
}

size_t TwoWire::write(uint8_t b) {
  if (txLength_ >= BUFFER) {
    txOverflow_ = true;
    return 0;
  }
  tx_[txLength_++] = b;
  return 1;
}

size_t TwoWire::write(const uint8_t* data, size_t length) {
  for (size_t i = 0; i < length; i++)
    if (!write(data[i])) return i;
  return length;
}

int TwoWire::available() { return rxLength_ - rxIndex_; }
int TwoWire::read() { return rxIndex_ < rxLength_ ? rx_[rxIndex_++] : -1; }
