import { describe, expect, it } from 'vitest';
import { micros, mm, mmPerS } from './format.ts';

describe('number formats', () => {
  it('never shows "-0": a value a hair below zero reads as zero', () => {
    expect(mm(-1e-12)).toBe('0.000 mm');
    expect(mm(-0.0004)).toBe('0.000 mm');
    expect(mm(-0.0006)).toBe('-0.001 mm');
    expect(mmPerS(-0.01)).toBe('0.0 mm/s');
  });

  it('shows a sync error too small to print as under 0.1 µs, not 0.0', () => {
    expect(micros(0)).toBe('< 0.1 µs');
    expect(micros(2.44)).toBe('2.4 µs');
    expect(micros(1500)).toBe('1.50 ms');
    expect(micros(NaN)).toBe('—');
  });
});
