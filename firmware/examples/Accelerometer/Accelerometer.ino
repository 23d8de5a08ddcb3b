// MAXL time-aligned data retrieval (the paper's §4.2 and Figure 7): a BNO055
// accelerometer on the tool head, sampled every 10 ms while the author
// subscribes to it. Each sample is stamped with this device's clock, which
// the author maps back to machine time to lay measured acceleration over the
// planned one.
//
// Wiring: BNO055 breakout on SDA (A4), SCL (A5), 5 V (or 3.3 V), GND, ADR low.
#include <MAXL.h>

#include "bno055.h"

const uint32_t SAMPLE_PERIOD_US = 10000;  // 100 Hz

MAXL_Device maxl("accelerometer");
MAXL_SensorWriter accel("accel", 3);  // x, y, z in mm/s²
Bno055 imu;
bool imuReady = false;
uint32_t lastSample = 0;

void setup() {
  imuReady = imu.begin();
  maxl.begin(Serial);
}

void loop() {
  maxl.loop();
  if (!accel.subscribed()) return;
  uint32_t now = micros();
  if (!imuReady) {  // plugged in late, or the first try failed: retry once a second
    if ((int32_t)(now - lastSample) < 1000000L) return;
    lastSample = now;
    imuReady = imu.begin();
    return;
  }
  if ((int32_t)(now - lastSample) < (int32_t)SAMPLE_PERIOD_US) return;
  lastSample += SAMPLE_PERIOD_US;
  if ((int32_t)(now - lastSample) > (int32_t)SAMPLE_PERIOD_US) lastSample = now;  // fell behind: skip ahead
  float xyz[3];
  if (imu.readAcceleration(xyz)) accel.writeAt(now, xyz);  // stamped when the read began
}
