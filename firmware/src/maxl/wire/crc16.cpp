#include "maxl/wire/crc16.h"

namespace maxl_fw {

uint16_t crc16(const uint8_t* data, uint8_t length) {
  uint16_t crc = CRC16_INIT;
  for (uint8_t i = 0; i < length; i++) crc = crc16Update(crc, data[i]);
  return crc;
}

}  // namespace maxl_fw
