/**
 * CSV that a spreadsheet opens as data, never as formulas (CSV injection).
 *
 * Excel, LibreOffice and Google Sheets evaluate a cell whose text starts with
 * `=`, `+`, `-` or `@` as a formula, and tab or carriage return at the start can smuggle
 * one in after a separator. A device name or a channel name comes from firmware, which
 * the person exporting did not write, so every text cell is neutralised as OWASP's
 * "CSV Injection" page advises: a leading apostrophe makes the cell plain text, and the
 * CSV writer (d3-dsv) quotes cells holding a separator, a quote or a line break.
 *
 * Real numbers stay numbers: a JavaScript number is written as itself (`-12.5` is a
 * negative number to every spreadsheet, not a formula), and so is a text cell that is
 * exactly a decimal number. Anything else that starts with a trigger, `-1+2` or
 * `=HYPERLINK(…)`, gets the apostrophe.
 *
 * Every CSV the project writes goes through `formatSafeCsv` (or `safeCell`).
 */
import { csvFormatRows } from 'd3-dsv';

const TRIGGERS = new Set(['=', '+', '-', '@', '\t', '\r']);
/** A plain decimal number, as a spreadsheet reads one: sign, digits, point, exponent. */
const PLAIN_NUMBER = /^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/;

export type CsvCell = string | number | null | undefined;

/** One cell made safe: numbers as they are, text with a leading apostrophe if it could be read as a formula. */
export function safeCell(value: CsvCell): string | number | null {
  if (value === null || value === undefined) return null;
  if (typeof value === 'number') return value;
  if (value.length === 0 || !TRIGGERS.has(value[0]) || PLAIN_NUMBER.test(value)) return value;
  return `'${value}`;
}

/** CSV lines (RFC 4180 quoting by d3-dsv, joined by "\n", no line break after the last), every cell made safe. */
export function formatSafeCsvLines(rows: ReadonlyArray<readonly CsvCell[]>): string {
  return csvFormatRows(rows.map((row) => row.map((v) => {
    const cell = safeCell(v);
    return cell === null ? '' : String(cell);
  })));
}

/** CSV text (RFC 4180 quoting by d3-dsv) of a header row and data rows, every cell made safe. */
export function formatSafeCsv(header: readonly string[], rows: ReadonlyArray<readonly CsvCell[]>): string {
  return formatSafeCsvLines([header, ...rows]);
}
