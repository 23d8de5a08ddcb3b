import { describe, expect, it } from 'vitest';
import { silenceVerdict } from './silenceCheck.ts';

const silence_us = 300_000;

describe('the health check’s verdict', () => {
  it('is quiet enough while the device spoke within the silence limit', () => {
    expect(silenceVerdict({ now_us: 1_000_000, due_us: 1_000_000, lastHeard_us: 700_000, silence_us, previousHeldBack: false })).toBe('quiet-enough');
  });

  it('loses the link when a check on time finds the device silent for longer', () => {
    expect(silenceVerdict({ now_us: 1_000_000, due_us: 1_000_000, lastHeard_us: 699_000, silence_us, previousHeldBack: false })).toBe('lost');
    // late by less than a check period: still on time enough to judge
    expect(silenceVerdict({ now_us: 1_000_000, due_us: 925_000, lastHeard_us: 600_000, silence_us, previousHeldBack: false })).toBe('lost');
  });

  it('judges nothing when its own timer ran more than a period late (the author was held back), once', () => {
    const late = { now_us: 1_000_000, due_us: 900_000, lastHeard_us: 650_000, silence_us };
    expect(silenceVerdict({ ...late, previousHeldBack: false })).toBe('held-back');
    // held back at the next check too: a lost link is still found
    expect(silenceVerdict({ ...late, previousHeldBack: true })).toBe('lost');
  });
});
