#include "maxl/wire/frame_receiver.h"

#include "maxl/wire/crc16.h"

namespace maxl_fw {

void FrameReceiver::reset() {
  len_ = 0;
  encoded_ = 0;
  groupLeft_ = 0;
  zeroPending_ = false;
  overflow_ = false;
  crc_ = CRC16_INIT;
}

// Appends one decoded byte; the byte two places back is now known not to be
// part of the CRC, so it joins the running CRC.
void FrameReceiver::store(uint8_t b) {
  // encoded_ <= 65 guarantees len_ < 64 here (a frame of n encoded bytes
  // decodes to at most n - 1), so the buffer cannot overflow.
  if (len_ >= 2) crc_ = crc16Update(crc_, buf_[len_ - 2]);
  buf_[len_++] = b;
}

FrameReceiver::Result FrameReceiver::push(uint8_t byte, uint32_t now) {
  if (byte == 0) {
    arrivedAt_ = now;
    Result r = finish();
    reset();
    return r;
  }
  if (overflow_) return NOTHING;
  if (++encoded_ > MAX_ENCODED) {
    overflow_ = true;
    return NOTHING;
  }
  if (groupLeft_ == 0) {
    // A code byte: the previous group, if any, ends here with its zero.
    if (zeroPending_) store(0);
    groupLeft_ = (uint8_t)(byte - 1);
    zeroPending_ = byte < 0xFF;
  } else {
    store(byte);
    groupLeft_--;
  }
  return NOTHING;
}

FrameReceiver::Result FrameReceiver::finish() {
  if (overflow_) {
    error_ = CODEC_TOO_LONG;
    return ERROR;
  }
  if (encoded_ == 0) return NOTHING;  // empty frame: ignored
  if (groupLeft_ != 0) {
    error_ = CODEC_BAD_COBS;  // the last code byte pointed past the delimiter
    return ERROR;
  }
  if (len_ < 4) {
    error_ = CODEC_TOO_SHORT;
    return ERROR;
  }
  uint16_t received = (uint16_t)(buf_[len_ - 2] | ((uint16_t)buf_[len_ - 1] << 8));
  if (received != crc_) {
    error_ = CODEC_BAD_CRC;
    return ERROR;
  }
  packetLength_ = len_;
  return PACKET;
}

}  // namespace maxl_fw
