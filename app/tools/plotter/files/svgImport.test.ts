/**
 * SVG import: each element, nested transforms, viewBox and units, hidden and
 * unsupported elements, curves and arcs within the chord tolerance of their exact
 * shapes, and bad files refused with the element and line named.
 */
import { describe, expect, it } from 'vitest';
import { hausdorff } from '../geometry/hausdorff.ts';
import { FileImportError, type PlotPath } from './paths.ts';
import { importSvg } from './svgImport.ts';

/** A 100 × 100 mm page whose user unit is 1 mm. */
const page = (body: string, extra = '') => `<?xml version="1.0"?>
<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100" ${extra}>
${body}
</svg>`;

const pts = (p: PlotPath) => Array.from(p.points, (v) => Math.round(v * 1e6) / 1e6);
/** SVG user units (1 mm, y down) are the import's mm, y down too. */
const up = (xy: number[]) => xy;

function refused(text: string): FileImportError {
  try {
    importSvg('bad.svg', text);
  } catch (err) {
    expect(err).toBeInstanceOf(FileImportError);
    return err as FileImportError;
  }
  throw new Error('the file was accepted');
}

describe('SVG elements', () => {
  it('line, polyline and polygon (closed), in page mm (y down, the top-left corner at 0, 0)', () => {
    const d = importSvg('a.svg', page('<line x1="10" y1="10" x2="20" y2="30"/><polyline points="0,0 10,0 10,10"/><polygon points="50 50 60 50 60 60"/>'));
    expect(d.paths.map(pts)).toEqual([up([10, 10, 20, 30]), up([0, 0, 10, 0, 10, 10]), up([50, 50, 60, 50, 60, 60, 50, 50])]);
    expect(d.warnings).toEqual([]);
  });

  it('rect with and without rx/ry: corners are quarter ellipses, ry defaults to rx', () => {
    const d = importSvg('a.svg', page('<rect x="10" y="20" width="30" height="10"/><rect x="50" y="50" width="40" height="20" rx="5"/><rect x="0" y="0" width="10" height="10" rx="20" ry="2"/>'));
    expect(pts(d.paths[0])).toEqual(up([10, 20, 40, 20, 40, 30, 10, 30, 10, 20]));
    const rounded = d.paths[1];
    const xs = [], ys = [];
    for (let i = 0; i < rounded.points.length; i += 2) {
      xs.push(rounded.points[i]);
      ys.push(rounded.points[i + 1]);
    }
    expect(Math.min(...xs)).toBeCloseTo(50, 9);
    expect(Math.max(...xs)).toBeCloseTo(90, 9);
    expect(Math.min(...ys)).toBeCloseTo(50, 9);
    expect(Math.max(...ys)).toBeCloseTo(70, 9);
    // The corner at (50, 50): the straight top edge starts rx = 5 in, and the corner point itself is cut.
    expect(pts(rounded).slice(0, 2)).toEqual(up([55, 50]));
    expect(rounded.points.length / 2).toBeGreaterThan(12);
    // rx is clamped to half the width (5), ry given as 2.
    const clamped = d.paths[2];
    expect(pts(clamped).slice(0, 4)).toEqual(up([5, 0, 5, 0]));
  });

  it('circle and ellipse: every point on the exact curve, closed', () => {
    const d = importSvg('a.svg', page('<circle cx="50" cy="40" r="20"/><ellipse cx="30" cy="70" rx="15" ry="5"/>'));
    const [c, e] = d.paths;
    for (let i = 0; i < c.points.length; i += 2) expect(Math.hypot(c.points[i] - 50, c.points[i + 1] - 40)).toBeCloseTo(20, 9);
    for (let i = 0; i < e.points.length; i += 2) expect(((e.points[i] - 30) / 15) ** 2 + ((e.points[i + 1] - 70) / 5) ** 2).toBeCloseTo(1, 9);
    expect(pts(c).slice(0, 2)).toEqual(pts(c).slice(-2));
  });

  it('path commands: relative, H/V, S and T shorthands, several subpaths, Z returning to the start', () => {
    const d = importSvg('a.svg', page('<path d="M10 10 h10 v10 H10 z m30 0 l5 5 M60 60 Q70 50 80 60 T100 60"/>'));
    expect(d.paths).toHaveLength(3);
    expect(pts(d.paths[0])).toEqual(up([10, 10, 20, 10, 20, 20, 10, 20, 10, 10]));
    // After z the current point is the subpath's start: m30 0 is relative to (10, 10).
    expect(pts(d.paths[1])).toEqual(up([40, 10, 45, 15]));
    const q = d.paths[2];
    expect(pts(q).slice(-2)).toEqual(up([100, 60]));
    // T reflects the control point: the second half mirrors the first, to y = 65 below the line y = 60.
    const lowest = Math.max(...Array.from(q.points).filter((_, i) => i % 2 === 1));
    expect(lowest).toBeCloseTo(65, 6);
  });
});

describe('SVG transforms, viewBox and units', () => {
  it('nested groups compose transforms innermost first', () => {
    const d = importSvg('a.svg', page('<g transform="translate(50,50)"><g transform="rotate(90)"><line x1="0" y1="0" x2="10" y2="0" transform="scale(2)"/></g></g>'));
    // (10, 0) → scale 2 → (20, 0) → rotate 90° → (0, 20) → translate → (50, 70).
    expect(pts(d.paths[0])).toEqual(up([50, 50, 50, 70]));
  });

  it('matrix, skewX and a list of transforms in one attribute', () => {
    const d = importSvg('a.svg', page('<line x1="0" y1="10" x2="0" y2="20" transform="matrix(1 0 0 1 5 5) skewX(45)"/>'));
    // skewX(45): x += y; then translate (5, 5).
    expect(pts(d.paths[0])).toEqual(up([15, 15, 25, 25]));
  });

  it('viewBox scales to width/height in each unit (mm, cm, in, px at 96/in, pt, pc)', () => {
    for (const [w, mm] of [
      ['50mm', 50],
      ['5cm', 50],
      ['2in', 50.8],
      ['96px', 25.4],
      ['96', 25.4],
      ['72pt', 25.4],
      ['6pc', 25.4],
    ] as const) {
      const d = importSvg('a.svg', `<svg xmlns="http://www.w3.org/2000/svg" width="${w}" height="${w}" viewBox="0 0 10 10"><line x1="0" y1="10" x2="10" y2="10"/></svg>`);
      const v = Math.round(mm * 1e6) / 1e6;
      expect(pts(d.paths[0])).toEqual([0, v, v, v]);
    }
  });

  it('no viewBox: user units are px; a viewBox with an offset and "meet" keeps the aspect and centres', () => {
    const plain = importSvg('a.svg', '<svg xmlns="http://www.w3.org/2000/svg" width="96px" height="96px"><line x1="0" y1="0" x2="96" y2="0"/></svg>');
    expect(pts(plain.paths[0])).toEqual([0, 0, 25.4, 0]);
    // A 20 × 10 box in a 100 × 100 mm viewport: scale 5, centred vertically (25 mm above and below).
    const meet = importSvg('a.svg', '<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="10 10 20 10"><line x1="10" y1="10" x2="30" y2="20"/></svg>');
    expect(pts(meet.paths[0])).toEqual([0, 25, 100, 75]);
  });

  it('lengths with units inside the drawing (r="5mm") are converted to user units', () => {
    const d = importSvg('a.svg', '<svg xmlns="http://www.w3.org/2000/svg" width="96px" height="96px"><circle cx="1in" cy="1in" r="5mm"/></svg>');
    const c = d.paths[0];
    for (let i = 0; i < c.points.length; i += 2) expect(Math.hypot(c.points[i] - 25.4, c.points[i + 1] - 25.4)).toBeCloseTo(5, 6);
  });
});

describe('<use>: Inkscape clones and symbols', () => {
  const xlink = 'xmlns:xlink="http://www.w3.org/1999/xlink"';

  it('draws the element it refers to (xlink:href or href), moved by x, y and its own transform', () => {
    const d = importSvg(
      'clones.svg',
      page(
        `<defs><g id="tick" transform="translate(1 0)"><line x1="0" y1="0" x2="0" y2="5"/></g></defs>
<use xlink:href="#tick" x="10" y="20"/>
<use href="#tick" transform="translate(30 0)" x="0" y="20"/>
<line id="base" x1="0" y1="90" x2="10" y2="90"/>
<use xlink:href="#base" transform="rotate(90 50 50)"/>`,
        xlink,
      ),
    );
    expect(d.paths.map(pts)).toEqual([up([11, 20, 11, 25]), up([31, 20, 31, 25]), up([0, 90, 10, 90]), up([10, 0, 10, 10])]);
    expect(d.warnings).toEqual([]);
    // A clone's segments come from the line of the element drawn.
    expect(Array.from(d.paths[0].lines ?? [])).toEqual([3]);
  });

  it('a <symbol> without a viewBox draws as a group; one with a viewBox, a missing target and an external one are named', () => {
    const d = importSvg(
      'symbols.svg',
      page(
        `<symbol id="s"><line x1="0" y1="0" x2="4" y2="0"/></symbol>
<symbol id="v" viewBox="0 0 1 1"><line x1="0" y1="0" x2="1" y2="0"/></symbol>
<use href="#s" x="5" y="5"/><use href="#v"/><use href="#nothing"/><use href="other.svg#s"/>`,
      ),
    );
    expect(d.paths.map(pts)).toEqual([up([5, 5, 9, 5])]);
    expect(d.warnings.map((w) => w.message)).toEqual([
      '<use> is not drawn: it refers to a <symbol> with its own viewBox, which this importer does not scale',
      '<use> is not drawn: it refers to "#nothing", and no element has that id',
      '<use> is not drawn: it refers to "other.svg#s", outside this file',
    ]);
  });

  it('a <use> that refers to itself, or to a group around it, is refused', () => {
    expect(refused(page('<g id="loop"><line x1="0" y1="0" x2="1" y2="1"/>\n<use href="#loop" x="1"/></g>')).message).toMatch(
      /^line \d+: <use> refers to "#loop", which contains it: the copies would never end$/,
    );
  });
});

describe('what is not drawn', () => {
  it('skips defs, display:none (attribute or style) and hidden elements, and names unsupported ones', () => {
    const d = importSvg(
      'a.svg',
      page(`<defs><path d="M0 0 L10 10"/></defs>
<g style="display: none"><line x1="0" y1="0" x2="1" y2="1"/></g>
<line display="none" x1="0" y1="0" x2="1" y2="1"/>
<g visibility="hidden"><line x1="0" y1="0" x2="2" y2="2"/><line visibility="visible" x1="3" y1="3" x2="4" y2="4"/></g>
<text x="10" y="10">hello</text>
<line x1="5" y1="5" x2="6" y2="6"/>`),
    );
    expect(d.paths.map(pts)).toEqual([up([3, 3, 4, 4]), up([5, 5, 6, 6])]);
    expect(d.warnings).toEqual([{ line: 7, message: '<text> is not drawn: only path, line, polyline, polygon, rect, circle and ellipse are' }]);
  });

  it('names a shape that draws nothing (r = 0)', () => {
    const d = importSvg('a.svg', page('<circle id="dot" cx="1" cy="1" r="0"/><line x1="0" y1="0" x2="1" y2="1"/>'));
    expect(d.warnings).toEqual([{ line: 3, message: '<circle id="dot"> draws nothing: its r is 0' }]);
  });
});

describe('curves within the chord tolerance of the exact shape', () => {
  /** Dense samples of an exact curve, in the import's mm. */
  const dense = (f: (t: number) => [number, number], n = 4000) => {
    const out = new Float64Array(2 * (n + 1));
    for (let i = 0; i <= n; i++) {
      const [x, y] = f(i / n);
      out[2 * i] = x;
      out[2 * i + 1] = y;
    }
    return out;
  };

  for (const tol of [0.02, 0.2]) {
    it(`a cubic Bézier, Hausdorff ≤ ${tol} mm`, () => {
      const P = [10, 80, 20, 0, 90, 100, 95, 10];
      const d = importSvg('a.svg', page(`<path d="M${P[0]} ${P[1]} C${P.slice(2).join(' ')}"/>`), { chordTolerance_mm: tol });
      const exact = dense((t) => {
        const u = 1 - t;
        const b = [u * u * u, 3 * u * u * t, 3 * u * t * t, t * t * t];
        return [b[0] * P[0] + b[1] * P[2] + b[2] * P[4] + b[3] * P[6], b[0] * P[1] + b[1] * P[3] + b[2] * P[5] + b[3] * P[7]];
      });
      const h = hausdorff([d.paths[0].points], [exact], tol / 10);
      expect(h).toBeLessThanOrEqual(tol * 1.05);
      // and not wildly finer than asked: at least a fifth of the tolerance is used
      expect(h).toBeGreaterThan(tol / 5);
    });

    it(`an arc under a rotating, non-uniform transform, Hausdorff ≤ ${tol} mm`, () => {
      // A circle of r = 20 about (0, 0), from 10° to 250° the positive (sweep = 1) way: the large arc.
      const r = 20, a0 = (10 * Math.PI) / 180, a1 = (250 * Math.PI) / 180;
      const p0 = [r * Math.cos(a0), r * Math.sin(a0)], p1 = [r * Math.cos(a1), r * Math.sin(a1)];
      const d = importSvg('a.svg', page(`<path transform="translate(50 50) rotate(30) scale(1.5 0.75)" d="M${p0.join(' ')} A${r} ${r} 0 1 1 ${p1.join(' ')}"/>`), { chordTolerance_mm: tol });
      const c = Math.cos(Math.PI / 6), s = Math.sin(Math.PI / 6);
      const exact = dense((t) => {
        const th = a0 + (a1 - a0) * t;
        const x = 1.5 * r * Math.cos(th), y = 0.75 * r * Math.sin(th);
        return [50 + c * x - s * y, 50 + s * x + c * y];
      });
      const h = hausdorff([d.paths[0].points], [exact], tol / 10);
      expect(h).toBeLessThanOrEqual(tol * 1.05);
      expect(h).toBeGreaterThan(tol / 5);
    });
  }
});

describe('bad files are refused whole, naming the element or line', () => {
  it('malformed XML: the line', () => {
    const e = refused('<svg xmlns="http://www.w3.org/2000/svg">\n<g>\n<line x1="0" y1="0" x2="1" y2="1"/>\n</svg>');
    expect(e.message).toMatch(/malformed/);
    expect(e.line).toBeGreaterThan(0);
  });

  it('an empty file, a file that is not SVG, a file with nothing drawable', () => {
    expect(refused('').message).toBe('the file is empty');
    expect(refused('<html><body/></html>').message).toMatch(/not an SVG file: its root element is <html>/);
    expect(refused(page('<defs><circle r="5"/></defs><text>hi</text>')).message).toMatch(/no drawable geometry.*<text> is not drawn/);
  });

  it('bad path data, points, lengths, transforms and viewBox: the element and its line', () => {
    const bad = (body: string) => refused(page(`\n${body}`));
    expect(bad('<path id="p7" d="M0 0 L 10 x"/>').message).toMatch(/^line 4: <path id="p7"> has bad path data/);
    expect(bad('<polyline points="0 0 10"/>').message).toMatch(/^line 4: <polyline> has bad points/);
    expect(bad('<circle r="5%"/>').message).toMatch(/^line 4: <circle> has r="5%", which is not a length/);
    expect(bad('<rect width="10"/>').message).toMatch(/^line 4: <rect> has no height/);
    expect(bad('<g transform="spin(3)"><line x2="1"/></g>').message).toMatch(/^line 4: <line>.* has a bad transform "spin\(3\)"/);
    expect(refused('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10"><line x2="1"/></svg>').message).toMatch(/bad viewBox/);
  });
});
