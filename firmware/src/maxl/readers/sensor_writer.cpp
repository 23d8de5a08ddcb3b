#include "maxl/readers/sensor_writer.h"

#include "maxl/device/device.h"
#include "maxl/hal/hal.h"
#include "maxl/time/wrap.h"
#include "maxl/wire/bytes.h"

MAXL_SensorWriter::MAXL_SensorWriter(const char* name, uint8_t channels)
    : MAXL_Reader(name, maxl_fw::kind::SENSOR,
                  channels > MAXL_MAX_SENSOR_CHANNELS ? MAXL_MAX_SENSOR_CHANNELS : channels),
      used_(0),
      count_(0),
      sequence_(0),
      t0_(0),
      last_(0) {}

// Stamped with the device clock (mended after a jump, device.cpp readClock()).
bool MAXL_SensorWriter::write(const float* values) {
  MAXL_Device* d = MAXL_Device::instance();
  return writeAt(d ? d->clockNow() : maxl_fw::hal::micros(), values);
}

bool MAXL_SensorWriter::writeAt(uint32_t deviceTime, const float* values) {
  if (!subscribed()) return false;
  uint32_t dt = count_ ? deviceTime - last_ : 0;
  uint8_t size = (uint8_t)(maxl_fw::ByteWriter::varintSize(dt) + 4 * channels());
  if (count_ && (used_ + size > SPACE || count_ == 255)) {
    if (!flush()) return false;
    dt = 0;
    size = (uint8_t)(1 + 4 * channels());
  }
  if (size > SPACE) return false;
  if (count_ == 0) t0_ = deviceTime;
  maxl_fw::ByteWriter w(bytes_ + used_, (uint8_t)(SPACE - used_));
  w.varint(dt);
  for (uint8_t c = 0; c < channels(); c++) w.f32(values[c]);
  used_ = (uint8_t)(used_ + w.length());
  count_++;
  last_ = deviceTime;
  return true;
}

bool MAXL_SensorWriter::flush() {
  if (count_ == 0) return true;
  MAXL_Device* device = MAXL_Device::instance();
  if (device && !device->sendSamples(index(), sequence_, count_, t0_, bytes_, used_)) return false;
  sequence_++;
  used_ = 0;
  count_ = 0;
  return true;
}

void MAXL_SensorWriter::onTick(MAXL_Device& device) {
  if (count_ && maxl_fw::timeDiff(device.now(), t0_) >= (int32_t)MAXL_SAMPLE_MAX_AGE_US) flush();
}

void MAXL_SensorWriter::onUnsubscribe() {
  used_ = 0;
  count_ = 0;
}
