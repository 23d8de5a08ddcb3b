// A sensor reader (kind 5): the device writes samples, stamped with its own
// clock, and sends them to the author in SAMPLES batches (protocol §4).
//
//   MAXL_SensorWriter accel("accel", 3);
//   float xyz[3] = {...};
//   accel.write(xyz);            // stamped with the device clock now
//
// Samples are packed into one frame's payload as they come; a batch goes out
// when the next sample would not fit, when it is MAXL_SAMPLE_MAX_AGE_US old,
// or on flush(). Nothing is sent (and write() returns false) until the author
// subscribes the reader.
#ifndef MAXL_READERS_SENSOR_WRITER_H
#define MAXL_READERS_SENSOR_WRITER_H

#include <stdint.h>

#include "maxl/config.h"
#include "maxl/readers/reader.h"
#include "maxl/wire/protocol.h"

class MAXL_SensorWriter : public MAXL_Reader {
 public:
  MAXL_SensorWriter(const char* name, uint8_t channels);

  // False if the sample could not be kept: not subscribed, or the batch is
  // full and cannot go out yet (a frame is arriving on the link).
  bool write(const float* values);
  // With an explicit device time (e.g. when the sample was taken earlier).
  bool writeAt(uint32_t deviceTime, const float* values);
  // Sends the batch; false if it must wait (it is retried from loop()).
  bool flush();

  uint16_t batchesSent() const { return sequence_; }

 protected:
  void onTick(MAXL_Device& device);
  void onUnsubscribe();

 private:
  static const uint8_t SPACE = maxl_fw::MAX_PAYLOAD - 8;  // payload minus the SAMPLES header
  uint8_t bytes_[SPACE];
  uint8_t used_;
  uint8_t count_;
  uint16_t sequence_;
  uint32_t t0_;
  uint32_t last_;
};

#endif
