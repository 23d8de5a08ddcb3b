// libFuzzer target: a whole device (frame receiver, session, every handler,
// the motion state machine, events, readers) driven by arbitrary input, on
// the host hardware layer in virtual time, under ASan and UBSan.
//
// Random bytes rarely pass a CRC, so the input is a little program whose
// operations can also build valid frames around fuzzed payloads:
//   op % 5 == 0  raw bytes:   n = next % 48, then n bytes straight onto the link
//   op % 5 == 1  a frame:     seq mode, type, length, payload -> COBS + CRC
//   op % 5 == 2  time:        advance the clock by a fuzzed 8-, 16- or 32-bit step
//   op % 5 == 3  loops:       call loop() 1..16 times, 1..255 µs apart
// Stepper "a" steps from the (virtual) step timer, whose interrupts run while
// the clock advances; "b" steps from loop().
//   op % 5 == 4  payloads:    run a fuzzed payload through every codec parser
// After every operation, the device's invariants are checked and everything
// it sent must decode as valid frames; a violation aborts (a crash to libFuzzer).
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <new>

#include "MAXL.h"
#include "maxl/hal/hal_host.h"
#include "maxl/wire/frame_receiver.h"
#include "maxl/wire/frame_writer.h"
#include "maxl/wire/messages.h"

using namespace maxl_fw;

namespace {

void onPosition(float, float) {}
void onValue(float) {}

// Every kind of reader, as a sketch would declare them.
MAXL_Stepper stepperA("a", 2, 5, 80.0f);
MAXL_Stepper stepperB("b", 3, 6, 3.3f, true);
MAXL_TrackPositionLinear position("x", onPosition);
MAXL_TrackVelocity velocity("v", onValue);
MAXL_TrackAcceleration acceleration("acc", onValue);
MAXL_TrackEvent eventA("e0", onValue);
MAXL_TrackEvent eventB("e1", onValue);
MAXL_SensorWriter sensor("s", 3);

alignas(MAXL_Device) unsigned char deviceStorage[sizeof(MAXL_Device)];

struct Input {
  const uint8_t* data;
  size_t size;
  size_t pos;
  bool more() const { return pos < size; }
  uint8_t byte() { return pos < size ? data[pos++] : 0; }
  uint32_t word(uint8_t bytes) {
    uint32_t v = 0;
    for (uint8_t i = 0; i < bytes; i++) v |= (uint32_t)byte() << (8 * i);
    return v;
  }
};

void check(bool ok, const char* what) {
  if (!ok) {
    fprintf(stderr, "invariant violated: %s\n", what);
    abort();
  }
}

// Everything the device wrote must be well-formed frames.
void drainTx() {
  OwnedFrameReceiver rx;
  const uint8_t* tx = host::tx();
  size_t n = host::txLength();
  for (size_t i = 0; i < n; i++) {
    FrameReceiver::Result r = rx.push(tx[i], 0);
    check(r != FrameReceiver::ERROR, "the device sent a bad frame");
    if (r == FrameReceiver::PACKET) {
      msg::DecodeContext ctx = {0, 3};
      uint8_t t = rx.type();
      if (t != type::SAMPLES) check(msg::checkPayload(t, rx.payload(), rx.payloadLength(), ctx) == CODEC_OK, "the device sent a malformed payload");
      check(t >= 0x41 && t <= 0x47, "the device sent an author-to-device type");
    }
  }
  check(!host::txOverflowed(), "tx log overflow");
  host::clearTx();
  host::clearPinLog();
}

void checkInvariants(const MAXL_Device& device) {
  const Motion& m = device.motion();
  const SegmentQueue& q = m.queue();
  check(q.count() <= MAXL_SEGMENT_CAPACITY, "queue over capacity");
  check(q.timed() <= q.count(), "more timed segments than segments");
  check(m.activeSlots() <= MAXL_POSITION_SLOTS, "active slots");
  check(device.state() <= state::HALTED, "state out of range");
  check(stepperA.usesStepTimer(), "stepper a lost its step timer");
  int16_t pending = stepperA.generator().channel().pending();
  check(pending >= -MAXL_STEP_RING * 127 && pending <= MAXL_STEP_RING * 127, "step ring over capacity");
}

// Moves the clock on by dt, running the step timer's interrupts on the way
// (a jump of 2^31 µs or more is the clock going back: no interrupts).
void advance(uint32_t dt) {
  if (dt < 0x80000000u)
    host::runStepTimer(host::micros() + dt);
  else
    host::setMicros(host::micros() + dt);
}

const uint8_t TYPES[] = {type::HELLO_REQUEST, type::PING_REQUEST, type::CLOCK, type::SUBSCRIBE, type::GEOMETRY,
                         type::TIMING, type::EVENTS, type::REPLACE_TAIL, type::HALT, type::STATUS_REQUEST};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  host::reset();
  host::setMicros(0xFFF00000u);  // every run crosses the u32 wrap within seconds
  MAXL_Device* device = new (deviceStorage) MAXL_Device("fuzz");
  device->begin();
  // a clean ring and timer for every input (the readers are static)
  stepperA.useStepTimer(false);
  check(stepperA.useStepTimer(true), "stepper a has no step timer");
  Input in = {data, size, 0};
  uint8_t seq = 0;
  while (in.more()) {
    uint8_t op = in.byte();
    switch (op % 5) {
      case 0: {
        uint8_t n = in.byte() % 48;
        uint8_t raw[48];
        for (uint8_t i = 0; i < n; i++) raw[i] = in.byte();
        host::pushRx(raw, n);
        device->loop();
        break;
      }
      case 1: {
        uint8_t mode = in.byte();
        uint8_t t = (mode & 0x80) ? in.byte() : TYPES[in.byte() % sizeof(TYPES)];
        uint8_t s = (mode & 0x40) ? in.byte() : seq;
        if (t == type::HELLO_REQUEST) s = 0;
        uint8_t n = in.byte() % (MAX_PAYLOAD + 1);
        OwnedFrameWriter w;
        ByteWriter& p = w.begin(s, t);
        for (uint8_t i = 0; i < n; i++) p.u8(in.byte());
        check(w.finish(), "frame writer");
        host::pushRx(w.frame(), w.frameLength());
        seq = (uint8_t)(s + 1);
        while (host::rxPending()) device->loop();
        break;
      }
      case 2: {
        uint8_t width = in.byte() % 3;
        advance(in.word(width == 0 ? 1 : width == 1 ? 2 : 4));
        device->loop();
        break;
      }
      case 3: {
        uint8_t n = (uint8_t)(1 + in.byte() % 16);
        uint8_t dt = in.byte();
        for (uint8_t i = 0; i < n; i++) {
          advance(1u + dt);
          device->loop();
        }
        break;
      }
      case 4: {
        uint8_t t = in.byte();
        uint8_t n = in.byte() % (MAX_PAYLOAD + 1);
        uint8_t payload[MAX_PAYLOAD];
        for (uint8_t i = 0; i < n; i++) payload[i] = in.byte();
        msg::DecodeContext ctx = {(uint8_t)(in.byte() % 15), (uint8_t)(in.byte() % 16)};
        CodecError e = msg::checkPayload(t, payload, n, ctx);
        check(e == CODEC_OK || e == CODEC_MALFORMED || e == CODEC_UNKNOWN_MESSAGE, "codec result");
        break;
      }
    }
    checkInvariants(*device);
    drainTx();
  }
  device->~MAXL_Device();
  return 0;
}
