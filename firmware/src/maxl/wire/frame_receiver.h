// Streaming frame receiver (docs/protocol.md §3).
//
// Bytes go in one at a time, as the UART delivers them. COBS is undone on the
// fly into one 64-byte packet buffer, and the CRC is updated two bytes behind
// the newest (the last two bytes of a packet are its CRC, and which bytes are
// last is only known at the delimiter). So each byte costs a few dozen cycles
// and a complete frame needs no second pass.
//
// A frame ends at 0x00. push() then reports either a packet (seq, type and
// payload, CRC checked and stripped) or one of the errors of §3:
//   more than 65 encoded bytes     TOO_LONG   (the rest up to 0x00 is dropped)
//   a code byte past the end       BAD_COBS
//   fewer than 4 packet bytes      TOO_SHORT
//   CRC mismatch                   BAD_CRC
// An empty frame (two delimiters in a row) is ignored.
//
// The packet is decoded into a buffer the caller owns (FRAME_BUFFER_SIZE
// bytes), so that a device can send its replies from the same buffer once it
// has read the packet: 66 bytes of RAM instead of 130 on a 2 KB board. Then
// nothing may be sent while inFrame(): it would overwrite the packet.
// OwnedFrameReceiver brings its own buffer.
#ifndef MAXL_WIRE_FRAME_RECEIVER_H
#define MAXL_WIRE_FRAME_RECEIVER_H

#include <stdint.h>

#include "maxl/wire/protocol.h"

namespace maxl_fw {

class FrameReceiver {
 public:
  enum Result : uint8_t { NOTHING = 0, PACKET, ERROR };

  explicit FrameReceiver(uint8_t* buffer) : buf_(buffer), packetLength_(4), arrivedAt_(0), error_(CODEC_OK) {
    reset();
  }

  // Feeds one byte. `now` is the device clock, kept as the frame's arrival
  // time when this byte is the delimiter (PONG.rxTime).
  Result push(uint8_t byte, uint32_t now);

  // After PACKET: the packet, valid until the next push().
  uint8_t seq() const { return buf_[0]; }
  uint8_t type() const { return buf_[1]; }
  const uint8_t* payload() const { return buf_ + 2; }
  uint8_t payloadLength() const { return (uint8_t)(packetLength_ - 4); }
  uint32_t arrivedAt() const { return arrivedAt_; }
  // Part of a frame has arrived (its packet is being written into the buffer).
  bool inFrame() const { return encoded_ > 0 || overflow_; }
  // After ERROR: why.
  CodecError error() const { return error_; }

  void reset();

 private:
  Result finish();
  void store(uint8_t b);

  uint8_t* buf_;  // FRAME_BUFFER_SIZE bytes; the packet uses the first MAX_PACKET
  uint8_t len_;           // decoded bytes stored so far
  uint8_t packetLength_;  // length of the last complete packet (push() resets len_)
  uint8_t encoded_;    // encoded bytes seen in this frame
  uint8_t groupLeft_;  // data bytes left in the current COBS group
  bool zeroPending_;   // the current group, once done, is followed by a zero (code < 255)
  bool overflow_;      // TOO_LONG: dropping up to the next delimiter
  uint16_t crc_;       // CRC over buf_[0 .. len_ - 3]
  uint32_t arrivedAt_;
  CodecError error_;
};

class OwnedFrameReceiver : public FrameReceiver {
 public:
  OwnedFrameReceiver() : FrameReceiver(own_) {}

 private:
  uint8_t own_[FRAME_BUFFER_SIZE];
};

}  // namespace maxl_fw

#endif
