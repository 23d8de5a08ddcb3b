/**
 * G-code → pen-down polylines in mm, into the same flow as an SVG.
 *
 * What it reads (everything else is listed as a warning with its line numbers):
 * - G0 (rapid) and G1 (feed) lines, F in units per minute (modal);
 * - G2 (clockwise) and G3 (counter-clockwise) arcs in the XY plane, by centre
 *   offsets I, J (always relative to the arc's start) or by radius R (R > 0 the
 *   shorter arc, R < 0 the longer), split within the chord tolerance;
 * - G4 dwell, P in ms or S in s (Marlin's reading), held with the pen down inside
 *   a stroke;
 * - G90/G91 absolute/relative coordinates, G20/G21 inches/mm, G17 and G94 (what
 *   we assume anyway);
 * - the pen: M3 (or M4) down and M5 up, or, in Z mode, down while Z is below a
 *   threshold; `auto` uses M3/M5 when the file has them, else Z;
 * - M2/M30 (program end; later lines are ignored, and that is said).
 *
 * A move is drawn when it ends with the pen down (M words act before the line's
 * motion; in Z mode the move's own Z decides). G0 with the pen down draws at the
 * pen-down speed, and says so. A feed above the machine's limit runs at the limit,
 * and says so.
 */
import { DEFAULT_CHORD_TOLERANCE_MM, flattenCenterArc } from './flatten.ts';
import { FileImportError, type Drawing, type FileWarning, type PlotPath } from './paths.ts';
import { tokenize, type Word } from './gcodeWords.ts';

export type GcodePenMode = 'auto' | 'm3m5' | 'z';

export interface GcodeImportOptions {
  chordTolerance_mm?: number;
  pen?: GcodePenMode;
  /** mm: in Z mode the pen is down while Z < this. */
  zThreshold_mm?: number;
  /** mm/s: the machine's top speed; faster feeds run at it, with a warning. */
  maxSpeed_mm_s?: number;
}

const PARAMS = new Set(['X', 'Y', 'Z', 'I', 'J', 'R', 'F', 'P', 'S']);
/** Lines listed per warning before "and N more". */
const LINES_LISTED = 10;

export function importGcode(name: string, text: string, options: GcodeImportOptions = {}): Drawing {
  const tol = options.chordTolerance_mm ?? DEFAULT_CHORD_TOLERANCE_MM;
  if (!(tol > 0)) throw new FileImportError(`the chord tolerance must be > 0 mm, got ${tol}`);
  if (text.trim() === '') throw new FileImportError('the file is empty');
  const lines = tokenize(text);
  const zThreshold = options.zThreshold_mm ?? 0;
  let mode = options.pen ?? 'auto';
  const notes: FileWarning[] = [];
  if (mode === 'auto') {
    const hasM3 = lines.some((l) => l.words.some((w) => w.letter === 'M' && (w.value === 3 || w.value === 4 || w.value === 5)));
    const hasZ = lines.some((l) => l.words.some((w) => w.letter === 'Z'));
    mode = hasM3 || !hasZ ? 'm3m5' : 'z';
    if (mode === 'z') notes.push({ message: `the file has no M3/M5, so the pen follows Z: down while Z < ${zThreshold} mm` });
  }
  const maxSpeed = options.maxSpeed_mm_s ?? Infinity;

  // Warnings gathered per kind, with their lines.
  const listed = new Map<string, number[]>();
  const note = (what: string, line: number) => {
    const at = listed.get(what);
    if (at) at.push(line);
    else listed.set(what, [line]);
  };

  const paths: PlotPath[] = [];
  let pts: number[] = [];
  let speeds: number[] = [];
  let dwells: number[] = [];
  /** Each segment's line in the file. */
  let segmentLines: number[] = [];
  const flush = () => {
    if (pts.length >= 4) {
      const anySpeed = speeds.some((v) => v !== 0);
      const anyDwell = dwells.some((v) => v !== 0);
      paths.push({
        points: Float64Array.from(pts),
        speeds: anySpeed ? Float64Array.from(speeds) : null,
        dwells: anyDwell ? Float64Array.from(dwells) : null,
        lines: Int32Array.from(segmentLines),
      });
    }
    pts = [];
    speeds = [];
    dwells = [];
    segmentLines = [];
  };
  /** The line being read. */
  let lineNow = 0;

  let x = 0, y = 0, z = 0;
  /** mm, the lowest and highest Z the file reaches (for the message when nothing goes below the threshold). */
  let zLow = Infinity, zHigh = -Infinity;
  let absolute = true;
  let unit = 1; // mm per file unit
  let motion: 0 | 1 | 2 | 3 | null = null;
  let feed = 0; // mm/s, 0 until an F
  let penDown = false;
  let ended = 0;

  /** Appends a pen-down point reached at `speed` mm/s (0: the setting). */
  const drawTo = (px: number, py: number, speed: number) => {
    if (pts.length === 0) {
      pts.push(x, y);
      dwells.push(0);
    }
    pts.push(px, py);
    speeds.push(speed);
    dwells.push(0);
    segmentLines.push(lineNow);
  };

  for (const { line, words, junk } of lines) {
    lineNow = line;
    if (ended) {
      note(`lines after the program's end (M2/M30 at line ${ended}) are ignored`, line);
      continue;
    }
    for (const j of junk) note(`"${j}" is not G-code`, line);
    const p: Partial<Record<string, Word>> = {};
    const codes: Word[] = [];
    for (const w of words) {
      if (w.letter === 'G' || w.letter === 'M') codes.push(w);
      else if (PARAMS.has(w.letter)) {
        if (p[w.letter]) throw new FileImportError(`${w.letter} appears twice`, line);
        p[w.letter] = w;
      } else note(`${w.text} is not supported (ignored)`, line);
    }
    let dwellHere = false;
    /** An unsupported G code owns the line's coordinates (G28 X0, G92 X0…): nothing on it moves. */
    let skipLine = false;
    let arcOrLine: 0 | 1 | 2 | 3 | null = null;
    for (const c of codes) {
      const v = c.value;
      if (c.letter === 'M') {
        if (v === 3 || v === 4) {
          if (mode === 'm3m5') penDown = true;
          else note(`${c.text} is ignored: the pen follows Z`, line);
          if (p.S && mode === 'm3m5') note(`S on M3 (a spindle or servo value) is not used: the pen settings set the pen's positions`, line);
        } else if (v === 5) {
          if (mode === 'm3m5') {
            penDown = false;
            flush();
          } else note(`${c.text} is ignored: the pen follows Z`, line);
        } else if (v === 2 || v === 30) ended = line;
        else note(`${c.text} is not supported (ignored)`, line);
        continue;
      }
      switch (v) {
        case 0:
        case 1:
        case 2:
        case 3:
          motion = v;
          arcOrLine = v;
          break;
        case 4:
          dwellHere = true;
          break;
        case 17:
        case 94:
          break;
        case 20:
          unit = 25.4;
          break;
        case 21:
          unit = 1;
          break;
        case 90:
          absolute = true;
          break;
        case 91:
          absolute = false;
          break;
        default:
          note(`${c.text} is not supported (the line is ignored)`, line);
          skipLine = true;
      }
    }
    if (skipLine) continue;
    if (p.F) {
      if (!(p.F.value > 0)) throw new FileImportError(`${p.F.text}: the feed rate must be > 0`, line);
      feed = (p.F.value * unit) / 60;
      if (feed > maxSpeed) note(`F${p.F.value} (${feed.toFixed(1)} mm/s) is above the machine's ${maxSpeed} mm/s: those moves run at ${maxSpeed} mm/s`, line);
    }
    if (dwellHere) {
      const s = p.P ? p.P.value / 1000 : p.S ? p.S.value : 0;
      if (!(s >= 0)) throw new FileImportError('G4 needs a dwell ≥ 0 (P in ms or S in s)', line);
      if (penDown && pts.length > 0) dwells[dwells.length - 1] += s;
      else if (penDown) {
        pts.push(x, y);
        dwells.push(s);
      } else note('G4 with the pen up is not kept (the pen settings already wait for the servo)', line);
      continue;
    }
    const hasXY = p.X !== undefined || p.Y !== undefined;
    const hasZ = p.Z !== undefined;
    if (!hasXY && !hasZ) {
      if (arcOrLine !== null && (p.I || p.J || p.R)) throw new FileImportError('an arc needs an end point (X or Y)', line);
      continue;
    }
    if (motion === null) {
      note('coordinates without G0/G1/G2/G3 before them are ignored', line);
      continue;
    }
    const nx = p.X ? (absolute ? 0 : x) + p.X.value * unit : x;
    const ny = p.Y ? (absolute ? 0 : y) + p.Y.value * unit : y;
    if (hasZ) {
      z = (absolute ? 0 : z) + (p.Z as Word).value * unit;
      zLow = Math.min(zLow, z);
      zHigh = Math.max(zHigh, z);
      if (mode === 'z') {
        const down = z < zThreshold;
        if (!down && penDown) flush();
        penDown = down;
      }
    }
    if (!penDown) {
      flush();
      x = nx;
      y = ny;
      continue;
    }
    const speed = motion === 0 ? 0 : Math.min(feed, maxSpeed);
    if (motion === 0) note('G0 with the pen down draws at the pen-down speed', line);
    if (motion === 0 || motion === 1) {
      if (nx !== x || ny !== y) drawTo(nx, ny, speed);
    } else {
      const arc = arcPoints(motion === 2, x, y, nx, ny, p, unit, tol, line, note);
      for (let i = 0; i < arc.length; i += 2) drawTo(arc[i], arc[i + 1], speed);
    }
    x = nx;
    y = ny;
  }
  flush();

  const warnings = [...notes];
  for (const [what, at] of listed) {
    const shown = at.slice(0, LINES_LISTED);
    const more = at.length - shown.length;
    warnings.push({ line: at[0], message: `${at.length > 1 ? 'lines' : 'line'} ${shown.join(', ')}${more > 0 ? ` and ${more} more` : ''}: ${what}` });
  }
  if (paths.length === 0) {
    // In Z mode, the heights the file uses say where the threshold belongs (Z0 down and Z5 up is common).
    const heights = zLow < zHigh ? ` (its Z goes from ${+zLow.toFixed(3)} to ${+zHigh.toFixed(3)} mm: set Import → Z threshold between its pen-down and pen-up heights, then open it again)` : '';
    const how = mode === 'z' ? `no move with Z below ${zThreshold} mm${heights}` : 'no move between an M3 and an M5';
    throw new FileImportError(`the file has no pen-down moves: ${how}`);
  }
  return { name, kind: 'gcode', paths, warnings };
}

/**
 * The points of a G2/G3 arc after its start, the last exactly (ex, ey).
 *
 * By R: the centre lies on the chord's perpendicular bisector at h = √(r² − d²/4)
 * from the chord's midpoint. Walking clockwise along the shorter arc keeps the
 * centre on the chord's right (seen from start to end); counter-clockwise, on its
 * left; a negative R (the longer arc) takes the other side.
 */
function arcPoints(
  clockwise: boolean,
  sx: number,
  sy: number,
  ex: number,
  ey: number,
  p: Partial<Record<string, Word>>,
  unit: number,
  tol: number,
  line: number,
  note: (what: string, line: number) => void,
): number[] {
  let cx: number, cy: number;
  if (p.R) {
    const r = p.R.value * unit;
    const dx = ex - sx, dy = ey - sy;
    const d = Math.hypot(dx, dy);
    if (d === 0) throw new FileImportError(`${p.R.text}: an arc by radius needs an end point different from its start (use I and J for a full circle)`, line);
    const reach = 4 * r * r - d * d;
    if (reach < -1e-6 * d * d) throw new FileImportError(`${p.R.text}: the end point is ${d.toFixed(3)} mm away, farther than the diameter`, line);
    const h = Math.sqrt(Math.max(0, reach)) / 2;
    // Left normal of the chord.
    const nx = -dy / d, ny = dx / d;
    const side = (clockwise ? -1 : 1) * (r < 0 ? -1 : 1);
    cx = (sx + ex) / 2 + side * h * nx;
    cy = (sy + ey) / 2 + side * h * ny;
  } else {
    if (!p.I && !p.J) throw new FileImportError(`G${clockwise ? 2 : 3} needs I and J (the centre) or R (the radius)`, line);
    cx = sx + (p.I ? p.I.value * unit : 0);
    cy = sy + (p.J ? p.J.value * unit : 0);
  }
  const r0 = Math.hypot(sx - cx, sy - cy);
  const r1 = Math.hypot(ex - cx, ey - cy);
  if (r0 === 0) throw new FileImportError('the arc has radius 0', line);
  if (Math.abs(r1 - r0) > Math.max(0.005, 1e-3 * r0)) {
    note(`an arc's end is ${Math.abs(r1 - r0).toFixed(3)} mm off its circle: it is drawn on the start's circle and joined to the end`, line);
  }
  const theta0 = Math.atan2(sy - cy, sx - cx);
  let dtheta = Math.atan2(ey - cy, ex - cx) - theta0;
  const full = sx === ex && sy === ey;
  if (clockwise) {
    if (dtheta >= 0 || full) dtheta -= 2 * Math.PI;
    if (dtheta < -2 * Math.PI) dtheta += 2 * Math.PI;
  } else {
    if (dtheta <= 0 || full) dtheta += 2 * Math.PI;
    if (dtheta > 2 * Math.PI) dtheta -= 2 * Math.PI;
  }
  const out: number[] = [];
  flattenCenterArc(out, { cx, cy, rx: r0, ry: r0, phi: 0, theta0, dtheta }, tol, [ex, ey]);
  return out;
}
