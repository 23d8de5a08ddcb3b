/**
 * A long-exposure photograph of an LED strip carried by the tool: each LED
 * adds its colour times the time it dwells over a spot.
 *
 *   image(p) += Σ_LED  rgb_LED · ∫ δ(p − (tool(t) + offset_LED)) dt
 *
 * Units: an 8-bit channel value times seconds (a red LED at 255 held still for
 * 10 ms adds 2.55 to one pixel's R).
 *
 * Integration: while any LED is lit, the exposure is cut into sub-intervals no
 * longer than `maxStep_us`, and each LED deposits rgb·Δt at its position in
 * the middle of each sub-interval, splatted bilinearly over the four nearest
 * pixel centres (so the total deposited is exact and a spot between pixels
 * still lands smoothly). Deposits outside the image are counted, not lost
 * silently.
 */
export interface LedStripConfig {
  /** Number of LEDs. */
  count: number;
  /** Position of LED 0 relative to the tool, mm. */
  origin_mm: [number, number];
  /** Spacing from one LED to the next, mm, as a vector along the strip. */
  pitch_mm: [number, number];
}

export interface ExposureImageConfig {
  /** Pixels across and down. */
  width: number;
  height: number;
  /** Size of a pixel, mm. */
  mmPerPixel: number;
  /** Machine position of the centre of pixel (0, 0), mm. Pixel (i, j) is at origin + (i, j)·mmPerPixel. */
  origin_mm: [number, number];
  /** Longest sub-interval of integration, µs. */
  maxStep_us: number;
}

export class LedExposure {
  /** RGB per pixel, row-major: index 3·(j·width + i) + channel. */
  readonly image: Float32Array;
  /** Exposure deposited outside the image, per channel (value·s). */
  readonly outside = new Float64Array(3);
  /** Current colour of each LED, 3 bytes per LED. */
  readonly colours: Uint8Array;
  private lit = false;

  constructor(
    readonly strip: LedStripConfig,
    readonly imageConfig: ExposureImageConfig,
  ) {
    this.image = new Float32Array(imageConfig.width * imageConfig.height * 3);
    this.colours = new Uint8Array(strip.count * 3);
  }

  get anyLit(): boolean {
    return this.lit;
  }

  /** The strip shows new colours (3 bytes per LED; extra LEDs beyond the strip are ignored, missing ones go dark). */
  show(rgb: Uint8Array): void {
    this.colours.fill(0);
    this.colours.set(rgb.subarray(0, this.colours.length));
    this.lit = this.colours.some((c) => c !== 0);
  }

  /**
   * Exposes the photograph from t0 to t1 with the current colours, given the
   * tool's position at any time in between.
   */
  expose(t0_us: number, t1_us: number, toolAt: (t_us: number) => [number, number]): void {
    if (!this.lit || t1_us <= t0_us) return;
    const steps = Math.ceil((t1_us - t0_us) / this.imageConfig.maxStep_us);
    const dt_us = (t1_us - t0_us) / steps;
    for (let k = 0; k < steps; k++) {
      const [x, y] = toolAt(t0_us + (k + 0.5) * dt_us);
      this.depositStrip(x, y, dt_us * 1e-6);
    }
  }

  private depositStrip(toolX: number, toolY: number, dt_s: number): void {
    const { origin_mm, pitch_mm, count } = this.strip;
    for (let led = 0; led < count; led++) {
      const r = this.colours[3 * led];
      const g = this.colours[3 * led + 1];
      const b = this.colours[3 * led + 2];
      if (r === 0 && g === 0 && b === 0) continue;
      const x = toolX + origin_mm[0] + led * pitch_mm[0];
      const y = toolY + origin_mm[1] + led * pitch_mm[1];
      this.splat(x, y, r * dt_s, g * dt_s, b * dt_s);
    }
  }

  /** Bilinear splat of one deposit at machine position (x, y). */
  private splat(x: number, y: number, r: number, g: number, b: number): void {
    const { width, height, mmPerPixel, origin_mm } = this.imageConfig;
    const fx = (x - origin_mm[0]) / mmPerPixel;
    const fy = (y - origin_mm[1]) / mmPerPixel;
    const i0 = Math.floor(fx);
    const j0 = Math.floor(fy);
    const wx = fx - i0;
    const wy = fy - j0;
    for (let dj = 0; dj <= 1; dj++) {
      for (let di = 0; di <= 1; di++) {
        const w = (di ? wx : 1 - wx) * (dj ? wy : 1 - wy);
        if (w === 0) continue;
        const i = i0 + di;
        const j = j0 + dj;
        if (i < 0 || j < 0 || i >= width || j >= height) {
          this.outside[0] += r * w;
          this.outside[1] += g * w;
          this.outside[2] += b * w;
          continue;
        }
        const p = 3 * (j * width + i);
        this.image[p] += r * w;
        this.image[p + 1] += g * w;
        this.image[p + 2] += b * w;
      }
    }
  }
}
