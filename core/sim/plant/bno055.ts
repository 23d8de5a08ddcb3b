/**
 * A BNO055 (Bosch 9-axis IMU) as its I2C registers, enough for firmware that
 * reads acceleration: the accelerometer side only (magnetometer, gyroscope and
 * fusion outputs read as zero, except gravity/linear acceleration in fusion
 * modes). Facts from the datasheet (BST-BNO055-DS000):
 *
 *   address 0x28 (COM3 low) or 0x29
 *   page 0: 0x00 CHIP_ID = 0xA0, 0x01 ACC_ID = 0xFB, 0x02 MAG_ID = 0x32,
 *           0x03 GYR_ID = 0x0F, 0x04/05 SW_REV = 0x0311, 0x06 BL_REV,
 *           0x07 PAGE_ID,
 *           0x08..0x0D ACC_DATA X/Y/Z (LSB, MSB), 0x28..0x2D LIA_DATA
 *           (linear acceleration), 0x2E..0x33 GRV_DATA (gravity),
 *           0x34 TEMP, 0x35 CALIB_STAT, 0x36 ST_RESULT (0x0F: self-test
 *           passed), 0x39 SYS_STATUS, 0x3A SYS_ERR, 0x3B UNIT_SEL
 *           (bit 0: 0 = m/s², 1 = mg), 0x3D OPR_MODE (0 CONFIG, 1 ACCONLY,
 *           …, 8–12 fusion), 0x3E PWR_MODE, 0x3F SYS_TRIGGER (bit 5 RST_SYS),
 *           0x41 AXIS_MAP_CONFIG (default 0x24), 0x42 AXIS_MAP_SIGN
 *   page 1: 0x08 ACC_Config: bits 1:0 range (±2/4/8/16 g), bits 4:2
 *           bandwidth (7.81, 15.63, 31.25, 62.5, 125, 250, 500, 1000 Hz);
 *           default 0x0D = ±4 g, 62.5 Hz
 *   units: acceleration 1 m/s² = 100 LSB, or 1 mg = 1 LSB; int16 little-endian
 *
 * I2C: a write sends the register address then optional data (written with
 * auto-increment); a read returns bytes from the register pointer on, also
 * auto-incrementing. Data registers read 0 in CONFIG mode, as on the chip.
 *
 * Sampling: in non-fusion modes the accelerometer delivers samples at twice
 * its bandwidth; in fusion modes at 100 Hz. Each sample holds the average
 * specific force over its sample period (a boxcar filter standing in for the
 * chip's low-pass), plus Gaussian noise with the datasheet's density
 * (150 µg/√Hz) over the bandwidth, clipped to the range.
 *
 * Not modelled: the power-on and mode-switch delays (the chip answers at once),
 * calibration, interrupts, temperature.
 */
import { gaussian } from '../../random.ts';

export const BNO055_ADDRESS = 0x28;
export const BNO055_CHIP_ID = 0xa0;

export const Bno055Register = {
  CHIP_ID: 0x00,
  ACC_ID: 0x01,
  MAG_ID: 0x02,
  GYR_ID: 0x03,
  SW_REV_ID_LSB: 0x04,
  SW_REV_ID_MSB: 0x05,
  BL_REV_ID: 0x06,
  PAGE_ID: 0x07,
  ACC_DATA_X_LSB: 0x08,
  LIA_DATA_X_LSB: 0x28,
  GRV_DATA_X_LSB: 0x2e,
  TEMP: 0x34,
  CALIB_STAT: 0x35,
  ST_RESULT: 0x36,
  SYS_STATUS: 0x39,
  SYS_ERR: 0x3a,
  UNIT_SEL: 0x3b,
  OPR_MODE: 0x3d,
  PWR_MODE: 0x3e,
  SYS_TRIGGER: 0x3f,
  AXIS_MAP_CONFIG: 0x41,
  AXIS_MAP_SIGN: 0x42,
  /** page 1 */
  ACC_CONFIG: 0x08,
} as const;

export const Bno055Mode = { CONFIG: 0x00, ACCONLY: 0x01, NDOF: 0x0c } as const;

const STANDARD_GRAVITY = 9.80665; // m/s²
const BANDWIDTHS_HZ = [7.81, 15.63, 31.25, 62.5, 125, 250, 500, 1000];
const RANGES_G = [2, 4, 8, 16];
const FUSION_RATE_HZ = 100;

export interface Bno055Config {
  address: number;
  /** Accelerometer noise density, µg/√Hz (datasheet: 150). */
  noiseDensity_ug: number;
}

/** The specific force on the sensor, machine frame, m/s², averaged over [t − window, t]. */
export type SpecificForceSource = (t_us: number, window_us: number) => [number, number, number];

interface Sample {
  index: number;
  /** machine frame, m/s², noise included, before the axis remap and clipping */
  accel: [number, number, number];
  gravity: [number, number, number];
}

export class Bno055 {
  private readonly page0 = new Uint8Array(128);
  private readonly page1 = new Uint8Array(128);
  private pointer = 0;
  private sample: Sample | null = null;
  /**
   * Every sample the chip produced while read, for tests: author time (the end of its
   * averaging window) and value (m/s², machine frame, with noise). With a number for
   * recordSamples, only about that many of the latest are kept.
   */
  readonly samplesTaken: Array<{ t_us: number; accel: [number, number, number]; truth: [number, number, number] }> = [];
  readonly record: boolean;
  private readonly recordLimit: number;

  constructor(
    readonly config: Bno055Config,
    private readonly specificForce: SpecificForceSource,
    private readonly random: () => number,
    options: { recordSamples?: boolean | number } = {},
  ) {
    const r = options.recordSamples ?? false;
    this.record = r !== false && r !== 0;
    this.recordLimit = typeof r === 'number' ? Math.max(1, Math.floor(r)) : Infinity;
    this.reset();
  }

  /** Power-on register values. */
  reset(): void {
    this.page0.fill(0);
    this.page1.fill(0);
    const r = Bno055Register;
    this.page0[r.CHIP_ID] = BNO055_CHIP_ID;
    this.page0[r.ACC_ID] = 0xfb;
    this.page0[r.MAG_ID] = 0x32;
    this.page0[r.GYR_ID] = 0x0f;
    this.page0[r.SW_REV_ID_LSB] = 0x11;
    this.page0[r.SW_REV_ID_MSB] = 0x03;
    this.page0[r.BL_REV_ID] = 0x15;
    this.page0[r.ST_RESULT] = 0x0f;
    this.page0[r.AXIS_MAP_CONFIG] = 0x24;
    this.page0[r.TEMP] = 25;
    this.page1[r.ACC_CONFIG] = 0x0d;
    this.page1[r.PAGE_ID] = 1;
    this.pointer = 0;
    this.sample = null;
  }

  get mode(): number {
    return this.page0[Bno055Register.OPR_MODE] & 0x0f;
  }

  private get fusion(): boolean {
    return this.mode >= 0x08;
  }

  get bandwidth_hz(): number {
    return BANDWIDTHS_HZ[(this.page1[Bno055Register.ACC_CONFIG] >> 2) & 7];
  }

  get range_g(): number {
    return RANGES_G[this.page1[Bno055Register.ACC_CONFIG] & 3];
  }

  /** Time between samples, µs: 1/(2·bandwidth), or 10 ms in fusion modes. */
  get samplePeriod_us(): number {
    return 1e6 / (this.fusion ? FUSION_RATE_HZ : 2 * this.bandwidth_hz);
  }

  /** Standard deviation of each axis's noise, m/s²: density · √bandwidth. */
  get noiseSigma_mps2(): number {
    return this.config.noiseDensity_ug * 1e-6 * STANDARD_GRAVITY * Math.sqrt(this.bandwidth_hz);
  }

  /** An I2C write transaction; returns the Arduino Wire status (0 ok, 2 address NACK). */
  i2cWrite(address: number, data: Uint8Array): number {
    if (address !== this.config.address) return 2;
    if (data.length === 0) return 0;
    this.pointer = data[0] & 0x7f;
    for (let i = 1; i < data.length; i++) this.writeRegister(this.pointer++ & 0x7f, data[i]);
    return 0;
  }

  /** An I2C read transaction at author time t; null if nobody answers at that address. */
  i2cRead(address: number, length: number, t_us: number): Uint8Array | null {
    if (address !== this.config.address) return null;
    const out = new Uint8Array(length);
    const page = this.page0[Bno055Register.PAGE_ID] === 1 ? this.page1 : this.page0;
    if (page === this.page0) this.refreshData(t_us);
    for (let i = 0; i < length; i++) out[i] = page[this.pointer++ & 0x7f];
    return out;
  }

  private writeRegister(reg: number, value: number): void {
    const r = Bno055Register;
    if (reg === r.PAGE_ID) {
      this.page0[r.PAGE_ID] = value & 1;
      this.page1[r.PAGE_ID] = value & 1;
      return;
    }
    if (this.page0[r.PAGE_ID] === 1) {
      // Sensor configuration is only writable in CONFIG mode.
      if (reg === r.ACC_CONFIG && this.mode === Bno055Mode.CONFIG) this.page1[reg] = value;
      return;
    }
    switch (reg) {
      case r.SYS_TRIGGER:
        if (value & 0x20) this.reset();
        return;
      case r.OPR_MODE:
        this.page0[reg] = value & 0x0f;
        this.page0[r.SYS_STATUS] = this.mode === Bno055Mode.CONFIG ? 0 : this.fusion ? 5 : 6;
        this.sample = null;
        return;
      case r.UNIT_SEL:
      case r.PWR_MODE:
      case r.AXIS_MAP_CONFIG:
      case r.AXIS_MAP_SIGN:
        if (reg === r.UNIT_SEL || this.mode === Bno055Mode.CONFIG) this.page0[reg] = value;
        return;
      default:
        return; // read-only or not modelled
    }
  }

  /** Fills the data registers with the sample current at t (sample-and-hold). */
  private refreshData(t_us: number): void {
    const r = Bno055Register;
    if (this.mode === Bno055Mode.CONFIG) {
      this.page0.fill(0, r.ACC_DATA_X_LSB, r.GRV_DATA_X_LSB + 6);
      return;
    }
    const period = this.samplePeriod_us;
    const index = Math.floor(t_us / period);
    if (!this.sample || this.sample.index !== index) this.sample = this.takeSample(index, period);
    const { accel, gravity } = this.sample;
    const linear: [number, number, number] = [accel[0] - gravity[0], accel[1] - gravity[1], accel[2] - gravity[2]];
    this.writeVector(r.ACC_DATA_X_LSB, accel);
    this.writeVector(r.LIA_DATA_X_LSB, this.fusion ? linear : [0, 0, 0]);
    this.writeVector(r.GRV_DATA_X_LSB, this.fusion ? gravity : [0, 0, 0]);
  }

  private takeSample(index: number, period_us: number): Sample {
    const t = index * period_us;
    const truth = this.specificForce(t, period_us);
    const sigma = this.noiseSigma_mps2;
    const accel: [number, number, number] = [
      truth[0] + sigma * gaussian(this.random),
      truth[1] + sigma * gaussian(this.random),
      truth[2] + sigma * gaussian(this.random),
    ];
    if (this.record) {
      this.samplesTaken.push({ t_us: t, accel, truth });
      // Trimmed a quarter at a time, so keeping a bounded record costs O(1) per sample.
      if (this.samplesTaken.length > this.recordLimit * 1.25) this.samplesTaken.splice(0, this.samplesTaken.length - this.recordLimit);
    }
    return { index, accel, gravity: [0, 0, STANDARD_GRAVITY] };
  }

  /** Remaps machine axes to the chip's output axes, converts units, clips to range, stores int16 LE. */
  private writeVector(reg: number, v: [number, number, number]): void {
    const map = this.page0[Bno055Register.AXIS_MAP_CONFIG];
    const sign = this.page0[Bno055Register.AXIS_MAP_SIGN];
    const mg = (this.page0[Bno055Register.UNIT_SEL] & 1) === 1;
    const lsbPerMps2 = mg ? 1000 / STANDARD_GRAVITY : 100;
    const limit = this.range_g * STANDARD_GRAVITY;
    for (let axis = 0; axis < 3; axis++) {
      const source = (map >> (2 * axis)) & 3; // which machine axis feeds output axis `axis`
      const negate = (sign >> (2 - axis)) & 1; // AXIS_MAP_SIGN: bit 2 = X, bit 1 = Y, bit 0 = Z
      let value = source < 3 ? v[source] : 0;
      if (negate) value = -value;
      value = Math.max(-limit, Math.min(limit, value));
      const raw = Math.max(-32768, Math.min(32767, Math.round(value * lsbPerMps2)));
      this.page0[reg + 2 * axis] = raw & 0xff;
      this.page0[reg + 2 * axis + 1] = (raw >> 8) & 0xff;
    }
  }
}
