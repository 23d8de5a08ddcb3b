/**
 * What a simulated link does to bytes, per direction. Defaults are shaped like
 * a USB full-speed CDC-ACM serial port on a quiet bus:
 *
 *   - USB full speed schedules transfers in 1 ms frames (SOF every 1000 µs).
 *     Host→device (bulk OUT) data written by the app goes out at the next
 *     frame boundary; device→host (bulk IN) data is collected when the host
 *     polls, once per frame in practice for CDC drivers. So each direction
 *     adds 0..1 ms of frame quantisation.
 *   - On top of that, each direction has a fixed one-way delay (driver,
 *     host-controller and firmware USB stack processing) and a random jitter,
 *     uniform in [jitterMin, jitterMax]. Defaults give a ping round trip of
 *     about 1.5–3 ms, what one measures on a Linux host with an Arduino-class
 *     native-USB board.
 *   - A frame carries at most `bytesPerFrame` bytes (full speed bulk: 19
 *     packets of 64 bytes = 1216 bytes in one frame on an otherwise idle bus),
 *     in packets of at most `packetBytes`.
 *   - Faults, off by default: each byte is corrupted (xor'ed with a random
 *     non-zero value) with probability `corruptionProbability`; each packet is
 *     lost whole with probability `lossProbability`.
 */
export interface LinkDirectionConfig {
  /** Fixed one-way delay after the frame boundary, µs. */
  baseDelay_us: number;
  /** Uniform jitter added to each frame's delivery, µs: [min, max]. */
  jitterMin_us: number;
  jitterMax_us: number;
  /** Probability that a byte arrives changed. */
  corruptionProbability: number;
  /** Probability that a whole USB packet is lost. */
  lossProbability: number;
}

export interface LinkConfig {
  /** USB frame period, µs (1000 at full speed). */
  framePeriod_us: number;
  /** Largest USB packet, bytes (64 for full-speed bulk). */
  packetBytes: number;
  /** Bytes one frame can carry per direction. */
  bytesPerFrame: number;
  /** Author (host) to device. */
  toDevice: LinkDirectionConfig;
  /** Device to author (host). */
  toAuthor: LinkDirectionConfig;
  /** Author time at which the link is cut (nothing passes either way after it); Infinity for never. */
  cutAt_us: number;
  /** Seed of this link's randomness (jitter, corruption, loss). */
  seed: number;
}

export const USB_FULL_SPEED_LINK: LinkConfig = {
  framePeriod_us: 1000,
  packetBytes: 64,
  bytesPerFrame: 19 * 64,
  toDevice: { baseDelay_us: 150, jitterMin_us: 0, jitterMax_us: 100, corruptionProbability: 0, lossProbability: 0 },
  toAuthor: { baseDelay_us: 250, jitterMin_us: 0, jitterMax_us: 250, corruptionProbability: 0, lossProbability: 0 },
  cutAt_us: Infinity,
  seed: 1,
};

/**
 * An Uno-class board: USB reaches a bridge chip (the 16U2), which passes bytes to
 * the ATmega328P over a 250 000 baud UART, 25 000 bytes/s (uartBytesPerSecond).
 * Shaped as 25 bytes per 1 ms frame; the USB delays stay as above.
 */
export const UNO_UART_LINK: LinkOverrides = { packetBytes: 25, bytesPerFrame: 25 };

/** A partial link config: any field left out takes the USB full-speed default. */
export interface LinkOverrides {
  framePeriod_us?: number;
  packetBytes?: number;
  bytesPerFrame?: number;
  toDevice?: Partial<LinkDirectionConfig>;
  toAuthor?: Partial<LinkDirectionConfig>;
  cutAt_us?: number;
  seed?: number;
}

export function resolveLinkConfig(overrides: LinkOverrides = {}, base: LinkConfig = USB_FULL_SPEED_LINK): LinkConfig {
  const config: LinkConfig = {
    framePeriod_us: overrides.framePeriod_us ?? base.framePeriod_us,
    packetBytes: overrides.packetBytes ?? base.packetBytes,
    bytesPerFrame: overrides.bytesPerFrame ?? base.bytesPerFrame,
    toDevice: { ...base.toDevice, ...overrides.toDevice },
    toAuthor: { ...base.toAuthor, ...overrides.toAuthor },
    cutAt_us: overrides.cutAt_us ?? base.cutAt_us,
    seed: overrides.seed ?? base.seed,
  };
  validateLinkConfig(config);
  return config;
}

function validateLinkConfig(c: LinkConfig): void {
  const fail = (field: string, why: string): never => {
    throw new RangeError(`link config ${field}: ${why}`);
  };
  if (!(c.framePeriod_us > 0)) fail('framePeriod_us', 'must be > 0');
  if (!(c.packetBytes >= 1 && Number.isInteger(c.packetBytes))) fail('packetBytes', 'must be a positive integer');
  if (!(c.bytesPerFrame >= c.packetBytes && Number.isInteger(c.bytesPerFrame))) fail('bytesPerFrame', 'must be an integer >= packetBytes');
  for (const [name, d] of [['toDevice', c.toDevice], ['toAuthor', c.toAuthor]] as const) {
    if (!(d.baseDelay_us >= 0)) fail(`${name}.baseDelay_us`, 'must be >= 0');
    if (!(d.jitterMin_us >= 0 && d.jitterMax_us >= d.jitterMin_us)) fail(`${name}.jitter`, 'needs 0 <= jitterMin_us <= jitterMax_us');
    if (!(d.corruptionProbability >= 0 && d.corruptionProbability <= 1)) fail(`${name}.corruptionProbability`, 'must be in [0, 1]');
    if (!(d.lossProbability >= 0 && d.lossProbability <= 1)) fail(`${name}.lossProbability`, 'must be in [0, 1]');
  }
}
