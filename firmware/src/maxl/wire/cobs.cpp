#include "maxl/wire/cobs.h"

namespace maxl_fw {

uint8_t cobsEncodeInPlace(uint8_t* buffer, uint8_t length) {
  uint8_t codePos = 0;  // where the current group's code byte goes
  uint8_t out = 1;      // next output position
  uint8_t code = 1;     // 1 + bytes in the current group
  for (uint8_t in = 1; in <= length; in++) {
    uint8_t b = buffer[in];
    if (b == 0) {
      buffer[codePos] = code;
      codePos = out++;
      code = 1;
    } else {
      buffer[out++] = b;
      if (++code == 0xFF) {
        buffer[codePos] = code;
        codePos = out++;
        code = 1;
      }
    }
  }
  buffer[codePos] = code;
  return out;
}

int16_t cobsDecode(const uint8_t* in, uint8_t length, uint8_t* out, uint8_t capacity) {
  uint8_t i = 0;
  uint8_t o = 0;
  while (i < length) {
    uint8_t code = in[i];
    if (code == 0 || (uint16_t)i + code > length) return -1;
    i++;
    for (uint8_t k = 1; k < code; k++) {
      if (o >= capacity) return -1;
      out[o++] = in[i++];
    }
    if (code < 0xFF && i < length) {
      if (o >= capacity) return -1;
      out[o++] = 0;
    }
  }
  return o;
}

}  // namespace maxl_fw
