/**
 * The plot a file panel's settings, checked before anything is read or planned
 * with them.
 *
 * A number field the user empties reaches the worker as null, and one they set to
 * 0 or below as that number. Unchecked, a scale of 0 collapsed the whole drawing
 * onto one point (and the panel offered to plot it), an empty scale crashed the
 * panel, and a speed of 0 came back as the planner's refusal of "line 12" of the
 * file, which the file had nothing to do with. So each field is checked here, by
 * the name the panel gives it, and the plan is refused until it is fixed.
 */
import { MIN_SPEED } from '../../../../core/index.ts';
import type { ImportSettings, PlotSettings } from './protocol.ts';

/** What is wrong with the settings, one sentence per field, in the panel's words; empty when nothing is. */
export function settingsProblems(imp: ImportSettings, plot: PlotSettings): string[] {
  const problems: string[] = [];
  const shown = (v: unknown) => (v === null || v === undefined || v === '' ? 'it is empty' : `it is ${String(v)}`);
  const check = (field: string, v: unknown, ok: (n: number) => boolean, rule: string) => {
    if (typeof v !== 'number' || !Number.isFinite(v) || !ok(v)) problems.push(`${field} must be ${rule} (${shown(v)}).`);
  };
  const a = plot.arrangement;
  if (!a.fit) check('Scale', a.scale, (n) => n > 0, 'a number above 0 (1 is the file’s true size; Rotate turns it)');
  check('Margin', a.margin_mm, (n) => n >= 0, 'a number of mm ≥ 0');
  check('Pen-down speed', plot.drawSpeed, (n) => n >= MIN_SPEED, `a speed of at least ${MIN_SPEED} mm/s`);
  check('Travel speed', plot.travelSpeed, (n) => n >= MIN_SPEED, `a speed of at least ${MIN_SPEED} mm/s`);
  check('Pen down delay', plot.penDelayDown_s, (n) => n >= 0, 'a number of seconds ≥ 0');
  check('Pen up delay', plot.penDelayUp_s, (n) => n >= 0, 'a number of seconds ≥ 0');
  if (plot.merge) check('The join distance', plot.mergeTolerance_mm, (n) => n >= 0, 'a number of mm ≥ 0');
  check('Chord tolerance', imp.chordTolerance_mm, (n) => n > 0, 'a number of mm above 0');
  check('Z threshold', imp.zThreshold_mm, () => true, 'a number of mm');
  return problems;
}
