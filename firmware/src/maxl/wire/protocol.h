// Numbers fixed by docs/protocol.md: type codes, nack reasons, reader kinds,
// states, flags and sizes. Nothing here has behaviour.
#ifndef MAXL_WIRE_PROTOCOL_H
#define MAXL_WIRE_PROTOCOL_H

#include <stdint.h>

namespace maxl_fw {

const uint8_t PROTOCOL_VERSION = 1;
const uint32_t CLOCK_HZ = 1000000UL;

// §3 framing
const uint8_t MAX_PACKET = 64;          // seq + type + payload + crc
const uint8_t MAX_PAYLOAD = 60;
const uint8_t MAX_ENCODED = 65;         // COBS(packet), without the 0x00 delimiter
// One buffer holds a received packet or a frame being sent (spare COBS code
// byte + packet + delimiter); the device shares one between both directions.
const uint8_t FRAME_BUFFER_SIZE = 1 + MAX_PACKET + 1;
const uint8_t MAX_NAME = 31;
const uint8_t DUPLICATE_WINDOW = 16;    // seqs before `expected` that count as duplicates

namespace type {
// author to device
const uint8_t HELLO_REQUEST = 0x01;
// the wire's PING (docs/protocol.md); the C++ name differs because the
// ATmega2560's <avr/io.h> defines PING (port G's input register) as a macro
const uint8_t PING_REQUEST = 0x02;
const uint8_t CLOCK = 0x03;
const uint8_t SUBSCRIBE = 0x04;
const uint8_t GEOMETRY = 0x05;
const uint8_t TIMING = 0x06;
const uint8_t EVENTS = 0x07;
const uint8_t REPLACE_TAIL = 0x08;
const uint8_t HALT = 0x09;
const uint8_t STATUS_REQUEST = 0x0A;
// device to author
const uint8_t HELLO = 0x41;
const uint8_t READER = 0x42;
const uint8_t ACK = 0x43;
const uint8_t NACK = 0x44;
const uint8_t PONG = 0x45;
const uint8_t STATUS = 0x46;
const uint8_t SAMPLES = 0x47;
}  // namespace type

// Nack reason codes (§4 "Nack reasons").
namespace nack {
const uint8_t BAD_CRC = 1;
const uint8_t UNKNOWN_MESSAGE = 2;
const uint8_t QUEUE_FULL = 3;
const uint8_t LATE_SEGMENT = 4;
const uint8_t ALREADY_STARTED = 5;
const uint8_t BAD_SUBSCRIPTION = 6;
const uint8_t VERSION_MISMATCH = 7;
const uint8_t OUT_OF_ORDER = 8;
const uint8_t MALFORMED = 9;
const uint8_t UNKNOWN_SEGMENT = 10;
const uint8_t CLOCK_JUMP = 11;  // TIMING after the device clock jumped (§6)
// OUT_OF_ORDER detail meaning "no session yet: send HELLO_REQUEST" (§3).
const uint16_t NO_SESSION_DETAIL = 0x100;
}  // namespace nack

// Reader kinds (§4 "Reader kinds").
namespace kind {
const uint8_t POSITION = 1;
const uint8_t VELOCITY = 2;
const uint8_t ACCELERATION = 3;
const uint8_t EVENT = 4;
const uint8_t SENSOR = 5;
}  // namespace kind

// STATUS.state
namespace state {
const uint8_t IDLE = 0;
const uint8_t RUNNING = 1;
const uint8_t BRAKING = 2;
const uint8_t STOPPED = 3;
const uint8_t HALTED = 4;
}  // namespace state

// STATUS.flags (sticky until the next HELLO_REQUEST)
namespace status_flag {
const uint8_t STARVED = 1 << 0;
const uint8_t LATE = 1 << 1;
const uint8_t QUEUE_FULL = 1 << 2;
const uint8_t EVENT_OVERFLOW = 1 << 3;
const uint8_t CLOCK_JUMP = 1 << 4;  // micros() leapt or ran backwards while timed (§6)
}  // namespace status_flag

const uint8_t GEOMETRY_HAS_P0 = 1 << 0;
const uint8_t TIMING_HAS_START = 1 << 0;

// TIMING phase kinds, two bits each in `shape`, low bits first.
namespace phase {
const uint8_t NONE = 0;
const uint8_t ACCELERATE = 1;
const uint8_t CRUISE = 2;
const uint8_t DECELERATE = 3;
}  // namespace phase

const uint8_t HALT_NOW = 0;
const uint8_t HALT_BRAKE_AT = 1;

// Why a frame or payload could not be used. Codec-level, shared by the
// receiver and the message parsers; the vectors file names them.
enum CodecError : uint8_t {
  CODEC_OK = 0,
  CODEC_TOO_LONG,
  CODEC_BAD_COBS,
  CODEC_TOO_SHORT,
  CODEC_BAD_CRC,
  CODEC_MALFORMED,
  CODEC_UNKNOWN_MESSAGE,
};

const char* codecErrorName(CodecError e);

}  // namespace maxl_fw

#endif
