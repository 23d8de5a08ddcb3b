/**
 * A device's crystal: a free-running u32 µs counter that started at some
 * offset, runs fast or slow by a few ppm, and wraps every 2³² µs (71.6 min).
 *
 *   micros(t) = floor(offset_us + t · (1 + ppm·10⁻⁶)) mod 2³²
 *
 * where t is author µs (the scheduler's now()). The author never sees this
 * mapping; it estimates it from ping exchanges (docs/design.md, decision 3), and
 * tests compare its estimate with `deviceTimeAt`.
 */
export interface DeviceClockConfig {
  /** Device µs at author time 0 (may be beyond 2³²; it is reduced). */
  offset_us: number;
  /** Rate error: +50 means the device counts 50 µs too many per second. */
  ppm: number;
}

const WRAP = 4294967296;

export class DeviceClock {
  /** The offset in force: the configured one, plus every jump so far. */
  private offset_us: number;

  constructor(readonly config: DeviceClockConfig) {
    this.offset_us = config.offset_us;
  }

  /**
   * A fault: the counter jumps by `delta_us` (a glitch, a firmware that rewrote its
   * timer). From then on, and as read for any time, the count is shifted by it.
   */
  jump(delta_us: number): void {
    this.offset_us += delta_us;
  }

  /** The device's unwrapped count at author time t (µs, float). */
  deviceTimeAt(t_us: number): number {
    return this.offset_us + t_us * (1 + this.config.ppm * 1e-6);
  }

  /** What micros() returns at author time t: the wrapped u32. */
  microsAt(t_us: number): number {
    const n = Math.floor(this.deviceTimeAt(t_us));
    return ((n % WRAP) + WRAP) % WRAP;
  }

  /**
   * The first author time at which the unwrapped device count reaches `deviceCount`
   * (inverse of deviceTimeAt, up to float rounding).
   */
  authorTimeAt(deviceCount: number): number {
    return (deviceCount - this.offset_us) / (1 + this.config.ppm * 1e-6);
  }
}
