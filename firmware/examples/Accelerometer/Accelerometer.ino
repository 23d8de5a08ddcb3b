// MAXL time-aligned data retrieval (the paper's §4.2 and Figure 7): a BNO055
// accelerometer on the tool head, sampled every 1 ms (1 kHz) while the author
// subscribes to it.
//
// 1 kHz is what the Uno's UART carries with room to spare: a SAMPLES frame holds
// 3 samples (14 bytes each: a 2-byte time step and 3 floats) in ~55 bytes on
// the wire, 18.3 bytes a sample, so 18 300 of the 25 000 bytes/s of 250 000
// baud (73 %); 2 kHz, the chip's own rate, would need 37 000. Its build flags
// (build_flags.txt) give it a transmit buffer of its own (MAXL_TX_BUFFER), so a
// batch never waits for a frame being received, and a segment queue of 2 (it
// reads no trajectory). Each sample is stamped with this device's clock, which
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

const uint32_t SAMPLE_PERIOD_US = 1000;  // 1 kHz
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
