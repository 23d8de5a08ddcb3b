import { describe, expect, it } from 'vitest';
import { LEAD_GROWTH_US, LeadWatch, NOTE_EVERY_US } from './leadWatch.ts';

describe('LeadWatch', () => {
  it('notes a lead grown by a hold-back, with both leads, at most once in a while', () => {
    const watch = new LeadWatch();
    watch.ready(19_300);
    expect(watch.check(1_000_000, 19_300 + LEAD_GROWTH_US - 1)).toBeNull();
    const note = watch.check(2_000_000, 95_000);
    expect(note?.code).toBe('LEAD');
    expect(note?.level).toBe('warning');
    expect(note?.message).toContain('streamed 95 ms ahead (19 ms when they became ready)');
    expect(watch.check(2_000_000 + NOTE_EVERY_US - 1, 140_000)).toBeNull();
    expect(watch.check(2_000_000 + NOTE_EVERY_US, 140_000)?.message).toContain('streamed 140 ms ahead');
  });

  it('says nothing where the margins do not follow the machine, and starts afresh for a new author', () => {
    const watch = new LeadWatch();
    expect(watch.check(0, 1e9)).toBeNull(); // no author yet
    watch.ready(NaN); // a simulated machine
    expect(watch.check(0, 1e9)).toBeNull();
    watch.ready(19_300);
    expect(watch.check(0, 60_000)).not.toBeNull();
    watch.ready(19_300);
    expect(watch.check(1, 60_000)).not.toBeNull();
  });
});
