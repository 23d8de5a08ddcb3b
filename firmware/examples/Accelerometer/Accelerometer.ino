// MAXL time-aligned data retrieval (the paper's §4.2 and Figure 7): a BNO055
// accelerometer on the tool head, sampled every 10 ms while the author
// subscribes to it. Each sample is stamped with this device's clock, which
// the author maps back to machine time to lay measured acceleration over the
// planned one.
//
// The stamp is the instant the reading represents, not the instant it was
// read: the chip averages over its sample period P (500 µs, bno055.h) and holds
// the latest sample, so a read at t returns a window that ended in (t − P, t],
// centred in (t − 3P/2, t − P/2]. Stamping t − P is within ±P/2 = ±250 µs of
// that centre, whatever the phase between our reads and the chip's samples.
//
// Wiring: BNO055 breakout on SDA (A4), SCL (A5), 5 V (or 3.3 V), GND, ADR low.
#include <MAXL.h>

#include "bno055.h"
#include "sample_pacer.h"

const uint32_t SAMPLE_PERIOD_US = 10000;  // 100 Hz
const uint32_t RETRY_PERIOD_US = 1000000;

MAXL_Device maxl("accelerometer");
MAXL_SensorWriter accel("accel", 3);  // x, y, z in mm/s²
Bno055 imu;
bool imuReady = false;
SamplePacer pacer;  // the samples' and the IMU retries' clock (sample_pacer.h)

void setup() {
  imuReady = imu.begin();
  maxl.begin(Serial);
  pacer.idle(micros());
}

void loop() {
  maxl.loop();
  uint32_t now = micros();
  if (!accel.subscribed()) {
    pacer.idle(now);
    return;
  }
  if (!imuReady) {  // plugged in late, or the first try failed: retry once a second
    if (pacer.due(now, RETRY_PERIOD_US)) imuReady = imu.begin();
    return;
  }
  if (!pacer.due(now, SAMPLE_PERIOD_US)) return;
  float xyz[3];
  // Read at `now` (the read is one bus transaction), stamped at the centre of the chip's window.
  if (imu.readAcceleration(xyz)) accel.writeAt(now - Bno055::SAMPLE_PERIOD_US, xyz);
}
