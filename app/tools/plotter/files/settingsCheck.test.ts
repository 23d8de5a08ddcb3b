import { describe, expect, it } from 'vitest';
import { DEFAULT_ARRANGEMENT } from './arrange.ts';
import type { ImportSettings, PlotSettings } from './protocol.ts';
import { settingsProblems } from './settingsCheck.ts';

const IMPORT: ImportSettings = { chordTolerance_mm: 0.02, gcodePen: 'auto', zThreshold_mm: 0 };
const PLOT: PlotSettings = { arrangement: DEFAULT_ARRANGEMENT, merge: true, mergeTolerance_mm: 0.05, sort: true, drawSpeed: 40, travelSpeed: 120, penDelayDown_s: 0.15, penDelayUp_s: 0.12 };
const empty = null as unknown as number;

describe('settingsProblems', () => {
  it('takes the defaults, and a fitted drawing whatever its scale field holds', () => {
    expect(settingsProblems(IMPORT, PLOT)).toEqual([]);
    expect(settingsProblems(IMPORT, { ...PLOT, arrangement: { ...DEFAULT_ARRANGEMENT, fit: true, scale: empty } })).toEqual([]);
  });

  it('names each bad field, empty (null), zero, negative or not finite, in the panel’s words', () => {
    const scale = (v: number) => settingsProblems(IMPORT, { ...PLOT, arrangement: { ...DEFAULT_ARRANGEMENT, scale: v } });
    expect(scale(0)).toEqual(['Scale must be a number above 0 (1 is the file’s true size; Rotate turns it) (it is 0).']);
    expect(scale(-1)[0]).toMatch(/^Scale must be .*\(it is -1\)\.$/);
    expect(scale(empty)[0]).toMatch(/^Scale must be .*\(it is empty\)\.$/);
    expect(scale(Infinity)[0]).toMatch(/\(it is Infinity\)/);
    expect(settingsProblems(IMPORT, { ...PLOT, drawSpeed: 0, travelSpeed: empty, penDelayUp_s: -0.1 })).toEqual([
      'Pen-down speed must be a speed of at least 0.001 mm/s (it is 0).',
      'Travel speed must be a speed of at least 0.001 mm/s (it is empty).',
      'Pen up delay must be a number of seconds ≥ 0 (it is -0.1).',
    ]);
    expect(settingsProblems({ ...IMPORT, chordTolerance_mm: empty, zThreshold_mm: NaN }, { ...PLOT, arrangement: { ...DEFAULT_ARRANGEMENT, margin_mm: -2 } })).toEqual([
      'Margin must be a number of mm ≥ 0 (it is -2).',
      'Chord tolerance must be a number of mm above 0 (it is empty).',
      'Z threshold must be a number of mm (it is NaN).',
    ]);
  });

  it('checks the join distance only when joining', () => {
    expect(settingsProblems(IMPORT, { ...PLOT, mergeTolerance_mm: -1 })).toHaveLength(1);
    expect(settingsProblems(IMPORT, { ...PLOT, merge: false, mergeTolerance_mm: -1 })).toEqual([]);
  });
});
