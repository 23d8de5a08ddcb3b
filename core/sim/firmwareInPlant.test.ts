/**
 * Real firmware examples, driven by hand over the simulated links, move the
 * plant: steps from a Stepper segment, pen strokes from the Blot's event
 * track, light from the LightPainter's, and accelerometer samples that go
 * through the example's I2C driver, the BNO055 model and SAMPLES frames.
 */
import { existsSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { VirtualScheduler } from '../time/virtualScheduler.ts';
import { nodeWasmLoader, PUBLIC_FIRMWARE_DIR } from './device/nodeWasmLoader.ts';
import { createSimulatedMachine } from './machine.ts';
import { PRESETS } from './presets/index.ts';
import { DeviceDriver } from './testing/drive.ts';

const firmwareDir = process.env.MAXL_FIRMWARE_DIR ?? PUBLIC_FIRMWARE_DIR;
const built = ['Stepper', 'Accelerometer', 'BlotPlotter', 'LightPainter'].every((e) => existsSync(`${firmwareDir}/${e}.wasm`));
const loader = nodeWasmLoader(firmwareDir);

async function machine(id: string) {
  const s = new VirtualScheduler();
  const sim = await createSimulatedMachine(PRESETS[id](), s, { seed: 3, loader });
  return { s, sim };
}

describe.skipIf(!built)(`firmware driving the plant${built ? '' : ` (skipped: Stepper, Accelerometer, BlotPlotter, LightPainter .wasm not built in ${firmwareDir})`}`, () => {
  it('Stepper: a 10 mm segment at 20 mm/s makes 800 steps, on time', async () => {
    const { s, sim } = await machine('accelRig');
    const motor = new DeviceDriver(s, sim, 'motorOne');
    s.at(1000, () => {
      motor.hello();
      motor.subscribe(0, 'position', 0);
      motor.cruise(0, [0], [10], 10, 50_000, 500_000);
    });
    // Halfway through, the motor is within a step of 5 mm.
    await s.runUntil(300_000);
    sim.sync();
    expect(Math.abs(sim.plant.motorPositions().x - 5)).toBeLessThanOrEqual(1 / 80);
    await s.runUntil(1_000_000);
    sim.sync();
    expect(motor.nacks()).toEqual([]);
    expect(sim.plant.motorSteps()).toEqual({ x: 800 });
    expect(sim.plant.motors.x.stepsBackward).toBe(0);
    // The last step (799.5 steps' worth of travel) came just before the end, at 550 ms.
    expect(sim.plant.motors.x.lastStep_us).toBeGreaterThan(549_000);
    expect(sim.plant.motors.x.lastStep_us).toBeLessThanOrEqual(550_000 + 20);
    // The tool has followed through the belt and settled.
    await s.runUntil(3_000_000);
    sim.sync();
    expect(sim.plant.tool().x.position).toBeCloseTo(10, 2);
    await sim.stop();
  });

  it('Accelerometer: SAMPLES carry the BNO055 model’s readings, stamped with the device clock, every 1 ms', async () => {
    const { s, sim } = await machine('accelRig');
    const imu = new DeviceDriver(s, sim, 'accelerometer');
    const motor = new DeviceDriver(s, sim, 'motorOne');
    s.at(1000, () => {
      imu.hello();
      imu.subscribe(0, 'sensor', 0);
      motor.hello();
      motor.subscribe(0, 'position', 0);
      motor.cruise(0, [0], [20], 20, 100_000, 200_000); // a jerk of a move: the belt rings
    });
    await s.runUntil(600_000);
    sim.sync();
    expect(imu.nacks()).toEqual([]);
    const samples = imu.client.of('SAMPLES').flatMap((b) => {
      let t = b.message.t0;
      return b.message.samples.map((x) => ((t = (t + x.dt) >>> 0), { device_us: t, values: x.values }));
    });
    expect(samples.length).toBeGreaterThan(450);
    const chip = sim.plant.accelerometer!;
    const period = chip.samplePeriod_us;
    let moving = 0;
    for (const x of samples) {
      const t = imu.authorTime(x.device_us, 300_000);
      // The example stamps a reading one chip period before its read (Accelerometer.ino): the
      // chip's sample current at the read, t + period; its int16 (1 m/s² = 100 LSB) ×10 is mm/s².
      const read = t + period;
      const taken = chip.samplesTaken.find((k) => k.t_us === Math.floor(read / period) * period);
      expect(taken, `chip sample for t = ${t}`).toBeDefined();
      // The stamp is within half a period of the centre of the sample's averaging window.
      expect(Math.abs(t - (taken!.t_us - period / 2))).toBeLessThanOrEqual(period / 2 + 1);
      const lsb = (v: number) => Math.round(v * 100) * 10 || 0; // (no −0)
      expect(x.values).toEqual([lsb(taken!.accel[0]), lsb(taken!.accel[1]), lsb(taken!.accel[2])]);
      expect(Math.abs(x.values[2] - 9807)).toBeLessThan(250); // gravity, with the noise of a 1000 Hz bandwidth (σ ≈ 46 mm/s²)
      if (Math.abs(x.values[0]) > 1000) moving++;
    }
    // The ringing belt shows: several samples above 1 m/s² along x.
    expect(moving).toBeGreaterThan(3);
    // Samples are 1 ms apart in device time (the example's SAMPLE_PERIOD_US), stamped at the
    // loop that took them: within a loop period (20 µs) of the 1 ms grid.
    const gaps = samples.slice(1).map((x, i) => (x.device_us - samples[i].device_us) >>> 0);
    for (const g of gaps) expect(Math.abs(g - 1_000)).toBeLessThanOrEqual(20);
    await sim.stop();
  });

  it('BlotPlotter: the pen event track drops the pen after its servo delay and draws the move', async () => {
    const { s, sim } = await machine('blotPlotter');
    const blot = new DeviceDriver(s, sim, 'blot');
    s.at(1000, () => {
      blot.hello();
      blot.subscribe(0, 'position', 0); // a
      blot.subscribe(1, 'position', 1); // b
      blot.subscribe(2, 'event', 0); // pen
      // x: 0 → 10 mm, y = 0: a = x + y and b = x − y both go 0 → 10.
      blot.cruise(0, [0, 0], [10, 10], 10, 100_000, 1_000_000);
      blot.events(0, 0, [
        { offset: 0, value: 1 },
        { offset: 600_000, value: 0 },
      ]);
    });
    await s.runUntil(2_000_000);
    sim.sync();
    expect(blot.nacks()).toEqual([]);
    expect(sim.plant.motorSteps()).toEqual({ a: 800, b: 800 });
    expect(sim.plant.carriage()).toEqual({ x: 10, y: 0 });
    const pen = sim.plant.pen!;
    // onPen(1) → 1900 µs (down), onPen(0) → 1000 µs (up); setup sent 1000 first.
    expect(pen.pulses.map((p) => p.pulse_us)).toEqual([1000, 1900, 1000]);
    expect(pen.transitions.map((tr) => tr.down)).toEqual([true, false]);
    expect(pen.transitions[0].t_us).toBeCloseTo(100_000 + 120_000, -2);
    expect(pen.transitions[1].t_us).toBeCloseTo(700_000 + 90_000, -2);
    const [stroke] = pen.strokes;
    // Drawn from about x = 1.2 mm (the pen lands 120 ms into the 10 mm/s move) to about 6.9 mm (it lifts at 690 ms).
    expect(stroke.x[0]).toBeCloseTo(1.2, 0);
    expect(stroke.x[stroke.x.length - 1]).toBeCloseTo(6.9, 0);
    expect(Math.max(...stroke.y.map(Math.abs))).toBeLessThan(0.01);
    await sim.stop();
  });

  it('LightPainter: the bitmap event track lights the strip, and the exposure holds colour × time', async () => {
    const { s, sim } = await machine('lightPainter');
    const painter = new DeviceDriver(s, sim, 'lightPainter');
    s.at(1000, () => {
      painter.hello();
      painter.subscribe(0, 'event', 0);
      painter.cruise(0, [], [], 10, 100_000, 1_000_000);
      painter.events(0, 0, [
        { offset: 0, value: 0b00000101 }, // LEDs 0 and 2
        { offset: 400_000, value: 0 },
      ]);
    });
    await s.runUntil(2_000_000);
    sim.sync();
    expect(painter.nacks()).toEqual([]);
    const leds = sim.plant.leds!;
    // 400 ms of (255, 60, 10) on two LEDs; the tool did not move (no motor was driven).
    let r = 0;
    let g = 0;
    for (let k = 0; k < leds.image.length; k += 3) {
      r += leds.image[k];
      g += leds.image[k + 1];
    }
    // The device's 400 ms is 400 ms·(1 − 120 ppm) of author time.
    expect(r).toBeCloseTo(2 * 255 * 0.4, 1);
    expect(g).toBeCloseTo(2 * 60 * 0.4, 1);
    // LED 0 sits 3.5 pitches below the tool, LED 2 1.5 pitches below.
    const { mmPerPixel, origin_mm, width } = leds.imageConfig;
    const pixelRed = (x: number, y: number) => leds.image[3 * (Math.round((y - origin_mm[1]) / mmPerPixel) * width + Math.round((x - origin_mm[0]) / mmPerPixel))];
    // Each LED's light lands on the pixels around its position (bilinear), 255 × 0.4 in all.
    const redAround = (x: number, y: number) => {
      let sum = 0;
      for (let dx = -1; dx <= 1; dx++) for (let dy = -1; dy <= 1; dy++) sum += pixelRed(x + dx * mmPerPixel, y + dy * mmPerPixel);
      return sum;
    };
    expect(redAround(0, -3.5 * 6.4)).toBeCloseTo(102, 1);
    expect(redAround(0, -1.5 * 6.4)).toBeCloseTo(102, 1);
    expect(redAround(0, -2.5 * 6.4)).toBe(0);
    await sim.stop();
  });
});
