// MAXL time-aligned data retrieval (the paper's §4.2 and Figure 7): a BNO055
// accelerometer on the tool head, sampled every 10 ms while the author
// subscribes to it. Each sample is stamped with this device's clock, which
// the author maps back to machine time to lay measured acceleration over the
// planned one.
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
  if (imu.readAcceleration(xyz)) accel.writeAt(now, xyz);  // stamped when the read began
}
