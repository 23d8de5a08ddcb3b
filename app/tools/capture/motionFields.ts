/**
 * The test motion's fields as the Capture tab labels them, and a refusal from
 * core/capture/testMotions.ts said in those words: “From (Hz): is empty” rather
 * than “fromHz: must be a positive number, got null”.
 */
import { TestMotionError, type TestMotion } from '../../../core/capture/testMotions.ts';

/** The label beside each field in CapturePanel.svelte. */
export const MOTION_FIELD_LABELS: Readonly<Record<string, string>> = {
  axis: 'Axis',
  fromHz: 'From (Hz)',
  toHz: 'To (Hz)',
  hzPerSecond: 'Sweep rate (Hz/s)',
  accelPerHz: 'Accel per Hz (mm/s²)',
  stroke_mm: 'Stroke (mm)',
  from: 'From',
  to: 'To',
  steps: 'Strokes',
};

/** Field names the core's sentences may cite (“must be above fromHz (10 Hz)”), not plain words like “from”. */
const CITED = /\b(fromHz|toHz|hzPerSecond|accelPerHz|stroke_mm)\b/g;

/** The first number field left empty (or not a number), by its label, or null. */
export function emptyField(motion: TestMotion): string | null {
  const numbers = motion.kind === 'sweep' ? (['fromHz', 'toHz', 'hzPerSecond', 'accelPerHz'] as const) : (['stroke_mm', 'from', 'to', 'steps'] as const);
  for (const name of numbers) {
    const v = (motion as unknown as Record<string, unknown>)[name];
    if (typeof v !== 'number' || Number.isNaN(v)) return MOTION_FIELD_LABELS[name];
  }
  return null;
}

/** A TestMotionError in the tab's words: the field's label, then the sentence with cited fields labelled. */
export function motionErrorWords(err: TestMotionError): string {
  const sentence = err.message.startsWith(`${err.field}: `) ? err.message.slice(err.field.length + 2) : err.message;
  const label = MOTION_FIELD_LABELS[err.field] ?? err.field;
  return `${label}: ${sentence.replace(CITED, (name) => `“${MOTION_FIELD_LABELS[name]}”`)}`;
}
