#include "maxl/wire/frame_writer.h"

#include "maxl/wire/cobs.h"
#include "maxl/wire/crc16.h"

namespace maxl_fw {

bool FrameWriter::finish() {
  if (writer_.failed()) {
    frameLength_ = 0;
    return false;
  }
  uint8_t packetLength = (uint8_t)(2 + writer_.length());
  uint16_t crc = crc16(buf_ + 1, packetLength);
  buf_[1 + packetLength] = (uint8_t)crc;
  buf_[2 + packetLength] = (uint8_t)(crc >> 8);
  packetLength += 2;
  uint8_t encoded = cobsEncodeInPlace(buf_, packetLength);
  buf_[encoded] = 0;
  frameLength_ = (uint8_t)(encoded + 1);
  return true;
}

}  // namespace maxl_fw
