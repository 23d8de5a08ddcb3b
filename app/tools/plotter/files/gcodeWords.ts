/**
 * G-code lines to words: the letter and number pairs of each line, and what could
 * not be read.
 *
 * A small tokenizer instead of a package: `gcode-parser` (the one we know of) reads
 * Node streams with Node's events and is little used, and what a plotter needs is
 * only this: strip comments (`;` to the end of the line, and `( … )`), a leading
 * `N` line number and a trailing `*` checksum, `%` tape marks; then letter +
 * number words, spaces allowed between them ("G1X10 Y-2.5", "G 1 X 10").
 */

export interface Word {
  /** Upper case. */
  letter: string;
  value: number;
  /** As written, for messages ("G01", "X1e2"…). */
  text: string;
}

export interface GcodeLine {
  /** 1-based. */
  line: number;
  words: Word[];
  /** Text that is neither a comment nor a word, as written. */
  junk: string[];
}

const WORD = /([A-Za-z])\s*([+-]?(?:\d+\.?\d*|\.\d+))/y;

export function tokenize(text: string): GcodeLine[] {
  const out: GcodeLine[] = [];
  const lines = text.split(/\r\n|\r|\n/);
  for (let i = 0; i < lines.length; i++) {
    let s = lines[i];
    const semi = s.indexOf(';');
    if (semi >= 0) s = s.slice(0, semi);
    s = s.replace(/\([^)]*\)?/g, ' ');
    s = s.replace(/\*\d+\s*$/, '');
    if (s.trim() === '%' || s.trim() === '') continue;
    const words: Word[] = [];
    const junk: string[] = [];
    let at = 0;
    while (at < s.length) {
      const c = s[at];
      if (c === ' ' || c === '\t') {
        at++;
        continue;
      }
      WORD.lastIndex = at;
      const m = WORD.exec(s);
      if (m) {
        words.push({ letter: m[1].toUpperCase(), value: Number(m[2]), text: m[0].replace(/\s+/g, '') });
        at = WORD.lastIndex;
      } else {
        let end = at + 1;
        while (end < s.length && s[end] !== ' ' && s[end] !== '\t' && !/[A-Za-z]/.test(s[end])) end++;
        junk.push(s.slice(at, end));
        at = end;
      }
    }
    // A leading N word is the line's number, not a command.
    if (words.length > 0 && words[0].letter === 'N') words.shift();
    if (words.length > 0 || junk.length > 0) out.push({ line: i + 1, words, junk });
  }
  return out;
}
