/** Small helpers for editing a machine configuration in forms. */
import type { LimitsConfig } from '../../core/index.ts';

/** "a, b" → ['a', 'b'] */
export function names(text: string): string[] {
  return text
    .split(',')
    .map((s) => s.trim())
    .filter((s) => s.length > 0);
}

/** A limit as the form shows it: a number, or numbers per axis separated by commas. */
export function limitText(v: LimitsConfig['maxVelocity']): string {
  if (v === undefined) return '';
  return Array.isArray(v) ? v.join(', ') : String(v);
}

/** The form's text back to a limit; text that is not numbers stays as NaN so that validation names the field. */
export function parseLimit(text: string): number | number[] | undefined {
  const t = text.trim();
  if (t === '') return undefined;
  if (t.includes(',')) return t.split(',').map((s) => Number(s.trim()));
  return Number(t);
}

export function parseOptionalNumber(text: string): number | undefined {
  const t = text.trim();
  return t === '' ? undefined : Number(t);
}
