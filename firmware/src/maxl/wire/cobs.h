// Consistent Overhead Byte Stuffing (Cheshire and Baker, 1999), as framed in
// docs/protocol.md §3: each group is a code byte c (1..255) followed by c - 1
// non-zero bytes; a zero follows every group whose code is below 255, except
// the last. The encoded bytes contain no 0x00, which ends a frame on the wire.
#ifndef MAXL_WIRE_COBS_H
#define MAXL_WIRE_COBS_H

#include <stdint.h>

namespace maxl_fw {

// Encodes `length` bytes found at buffer[1 .. length] in place, into
// buffer[0 .. result - 1]. The buffer must hold length + 1 bytes. Encoding in
// place works because the write position never passes the read position:
// each group's code byte lands where the previous group's zero (or the spare
// first byte) was. Returns the encoded length (length + 1 for packets under
// 254 bytes).
uint8_t cobsEncodeInPlace(uint8_t* buffer, uint8_t length);

// Decodes a whole encoded frame (without its 0x00). Returns the decoded length,
// or -1 if a code byte points past the end (BAD_COBS) or the output would not
// fit in `capacity`. `in` and `out` may be the same buffer.
int16_t cobsDecode(const uint8_t* in, uint8_t length, uint8_t* out, uint8_t capacity);

}  // namespace maxl_fw

#endif
