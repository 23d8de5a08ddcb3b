// Builds one outgoing frame (docs/protocol.md §3) in a single 66-byte buffer:
//
//   begin(seq, type)   packet header at buf[1..2]
//   payload()          a ByteWriter for the payload, at buf[3..]
//   finish()           appends the CRC (little-endian, like every integer),
//                      COBS-encodes in place into buf[0..], appends 0x00.
//
// The packet sits one byte to the right of the frame so that COBS can encode
// in place (see cobs.h): no second buffer. The buffer is the caller's
// (FRAME_BUFFER_SIZE bytes; see frame_receiver.h); OwnedFrameWriter brings its own.
#ifndef MAXL_WIRE_FRAME_WRITER_H
#define MAXL_WIRE_FRAME_WRITER_H

#include <stdint.h>

#include "maxl/wire/bytes.h"
#include "maxl/wire/protocol.h"

namespace maxl_fw {

class FrameWriter {
 public:
  explicit FrameWriter(uint8_t* buffer) : buf_(buffer), writer_(buffer + 3, MAX_PAYLOAD), frameLength_(0) {}

  ByteWriter& begin(uint8_t seq, uint8_t type) {
    buf_[1] = seq;
    buf_[2] = type;
    writer_ = ByteWriter(buf_ + 3, MAX_PAYLOAD);
    frameLength_ = 0;
    return writer_;
  }
  ByteWriter& payload() { return writer_; }

  // Returns false (and makes no frame) if the payload overflowed 60 bytes.
  bool finish();

  const uint8_t* frame() const { return buf_; }
  uint8_t frameLength() const { return frameLength_; }

 private:
  uint8_t* buf_;  // spare code byte + packet + delimiter: FRAME_BUFFER_SIZE bytes
  ByteWriter writer_;
  uint8_t frameLength_;
};

class OwnedFrameWriter : public FrameWriter {
 public:
  OwnedFrameWriter() : FrameWriter(own_) {}

 private:
  uint8_t own_[FRAME_BUFFER_SIZE];
};

}  // namespace maxl_fw

#endif
