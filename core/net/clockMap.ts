/**
 * A device's clock as the author models it: a line through a reference point,
 *   device_µs = deviceRef + (author_µs − authorRef) · rate     (mod 2³²)
 * Device clocks are free-running u32 µs counters that wrap every 71.6 minutes, so
 * the device side of the line is kept unwrapped (a float64 µs count) and reduced
 * mod 2³² only on the way to the wire. Readings coming back are unwrapped against
 * the model's prediction, which is right to far better than ±35 minutes.
 */
export const U32 = 0x1_0000_0000;

/** Wrap-safe difference a − b of two u32 device times, in −2³¹ … 2³¹−1. */
export function u32Diff(a: number, b: number): number {
  return ((a - b) | 0);
}

export class ClockMap {
  constructor(
    /** author µs at the reference point */
    readonly authorRef: number,
    /** device µs at the reference point, unwrapped */
    readonly deviceRef: number,
    /** device µs per author µs: 1 + drift (e.g. 1.0001 for a crystal 100 ppm fast) */
    readonly rate: number,
  ) {}

  /** The device's clock at author time t, unwrapped, unrounded. */
  toDeviceExact(author_us: number): number {
    return this.deviceRef + (author_us - this.authorRef) * this.rate;
  }

  /** The device's u32 clock reading at author time t, rounded to the µs. */
  toDevice(author_us: number): number {
    const d = Math.round(this.toDeviceExact(author_us)) % U32;
    return d < 0 ? d + U32 : d;
  }

  /** The author time of a u32 device reading, taking the wrap nearest the model. */
  toAuthor(device_u32: number, near_author_us: number): number {
    const predicted = this.toDeviceExact(near_author_us);
    const predictedU32 = ((Math.round(predicted) % U32) + U32) % U32;
    const unwrapped = Math.round(predicted) + u32Diff(device_u32, predictedU32);
    return this.authorRef + (unwrapped - this.deviceRef) / this.rate;
  }
}
