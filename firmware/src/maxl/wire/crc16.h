// CRC-16/CCITT-FALSE (docs/protocol.md §3): polynomial 0x1021, initial value
// 0xFFFF, no reflection, no final xor. Check value of "123456789": 0x29B1.
#ifndef MAXL_WIRE_CRC16_H
#define MAXL_WIRE_CRC16_H

#include <stdint.h>

#if defined(__AVR__)
#include <util/crc16.h>
#endif

namespace maxl_fw {

const uint16_t CRC16_INIT = 0xFFFF;

// One byte, without a table (no RAM, ~20 instructions). This is the byte-wise
// form of the bit-serial division: with x = (crc >> 8) ^ byte, the next crc is
//   (crc << 8) ^ T(x), where T(x) = x·0x1021 reduced,
// and T(x) for polynomial 0x1021 = x^12 + x^5 + 1 expands to the shifts below
// once x is first folded with x >> 4 (the terms of degree >= 8 feed back).
inline uint16_t crc16Update(uint16_t crc, uint8_t byte) {
#if defined(__AVR__)
  // avr-libc's hand-written version of the same CRC (polynomial 0x1021, no
  // reflection; the initial value is ours), about four times faster than the
  // shifts below compile to on AVR.
  return _crc_xmodem_update(crc, byte);
#endif
  uint8_t x = (uint8_t)((crc >> 8) ^ byte);
  x ^= (uint8_t)(x >> 4);
  return (uint16_t)((crc << 8) ^ ((uint16_t)x << 12) ^ ((uint16_t)x << 5) ^ (uint16_t)x);
}

uint16_t crc16(const uint8_t* data, uint8_t length);

}  // namespace maxl_fw

#endif
