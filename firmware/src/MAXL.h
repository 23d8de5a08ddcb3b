// MAXL reader library: an Arduino board reads its tracks of a distributed
// trajectory (Read, Peek and Gershenfeld, "MAXL: Distributed Trajectories for
// Modular Motion", SCF '23), in time with the author's clock.
//
//   #include <MAXL.h>
//   MAXL_Device maxl("motorOne");
//   MAXL_Stepper stepper("stepper", 2, 5, 80.0f);          // step, dir, steps/mm
//   void setup() { maxl.begin(Serial); }
//   void loop()  { maxl.loop(); }
//
// Readers (paper, Listings 3 and 4):
//   MAXL_TrackPositionLinear  (name, void cb(float positionMm, float deltaMm))
//   MAXL_TrackVelocity        (name, void cb(float mmPerS))
//   MAXL_TrackAcceleration    (name, void cb(float mmPerS2))
//   MAXL_TrackEvent           (name, void cb(float value))
//   MAXL_SensorWriter         (name, channels).write(values)
//   MAXL_Stepper              (name, stepPin, dirPin, stepsPerUnit, invert)
// The wire protocol is docs/protocol.md; capacities are in maxl/config.h.
#ifndef MAXL_H
#define MAXL_H

#include "maxl/config.h"
#include "maxl/device/device.h"
#include "maxl/readers/reader.h"
#include "maxl/readers/sensor_writer.h"
#include "maxl/readers/step_generator.h"
#include "maxl/readers/stepper.h"
#include "maxl/readers/tracks.h"

#if MAXL_STEP_TIMER && MAXL_HAL_ARDUINO
// Timer 1 as MAXL runs it for MAXL_Stepper's step interrupt: normal mode,
// free running at 2 counts per µs (clk/8), wrapping every 32.768 ms. The
// library uses OCR1B and TIMER1_COMPB only; OCR1A, OC1A (D9), its interrupt
// and ICR1 are free for the sketch on the same count, as long as it does not
// change the mode or the clock (examples/BlotPlotter/servo_pulse.h). Call it
// before using those; it does nothing the second time.
inline void MAXL_useTimer1() { maxl_fw::hal::stepTimerBegin(0); }
#endif

#endif
