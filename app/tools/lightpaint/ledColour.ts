/**
 * The colour a lit LED shows at cruise, from the user's colour, brightness and
 * gamma, packed for the `neopixelColour` event channel as 0xRRGGBB (a whole
 * number below 2^24, exact in the wire's 32-bit float).
 *
 * Gamma: the colour picker's values and the brightness are perceptual levels;
 * an LED's light is linear in its PWM value, so each channel's PWM value is
 * 255 · (level · brightness)^γ (γ = 2.2 is the usual NeoPixel correction;
 * γ = 1 sends the values as they are).
 */

/** '#rrggbb' → [r, g, b], or null if it is not such a colour. */
export function parseHexColour(hex: string): [number, number, number] | null {
  const m = /^#?([0-9a-f]{6})$/i.exec(hex.trim());
  if (!m) return null;
  const n = parseInt(m[1], 16);
  return [(n >> 16) & 255, (n >> 8) & 255, n & 255];
}

/** PWM values 0..255 per channel. */
export function ledColour(rgb: readonly [number, number, number], brightness: number, gamma: number): [number, number, number] {
  const b = Math.min(1, Math.max(0, brightness));
  return rgb.map((c) => Math.round(255 * Math.pow((Math.min(255, Math.max(0, c)) / 255) * b, gamma))) as [number, number, number];
}

export function packColour([r, g, b]: readonly [number, number, number]): number {
  return r * 65536 + g * 256 + b;
}
