/** Numbers with units, readable at a glance. */

export function mm(v: number, digits = 3): string {
  return Number.isFinite(v) ? `${fixed(v, digits)} mm` : '— mm';
}

/** toFixed, without the "-0.000" a value a hair below zero rounds to. */
function fixed(v: number, digits: number): string {
  const text = v.toFixed(digits);
  return Number(text) === 0 ? (0).toFixed(digits) : text;
}

export function mmPerS(v: number): string {
  return Number.isFinite(v) ? `${fixed(v, 1)} mm/s` : '— mm/s';
}

/** µs as µs or ms, whichever reads better. */
export function micros(us: number): string {
  if (!Number.isFinite(us)) return '—';
  if (Math.abs(us) < 0.05) return '< 0.1 µs';
  if (Math.abs(us) < 1000) return `${us.toFixed(us < 10 ? 1 : 0)} µs`;
  return `${(us / 1000).toFixed(2)} ms`;
}

export function ms(v: number): string {
  return Number.isFinite(v) ? `${v.toFixed(1)} ms` : '— ms';
}

export function duration(s: number): string {
  if (!Number.isFinite(s)) return '—';
  const total = Math.max(0, Math.round(s));
  const h = Math.floor(total / 3600);
  const m = Math.floor((total % 3600) / 60);
  const sec = total % 60;
  if (h > 0) return `${h} h ${String(m).padStart(2, '0')} min`;
  if (m > 0) return `${m} min ${String(sec).padStart(2, '0')} s`;
  return `${sec} s`;
}

export function count(n: number): string {
  return n.toLocaleString('en-US');
}

export function clock(at: number): string {
  const d = new Date(at);
  return d.toTimeString().slice(0, 8);
}
