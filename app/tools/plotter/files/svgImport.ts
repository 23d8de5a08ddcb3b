/**
 * SVG → pen-down polylines in mm on the page (y down, as in the file and on the
 * bed; the page's top-left corner at 0, 0).
 *
 * Libraries:
 * - The XML is parsed by @xmldom/xmldom, not the page's DOMParser: the import runs
 *   in the worker (beside the planner that times the plot) and in Node's tests,
 *   and neither has a DOMParser. xmldom is the W3C DOM in plain JavaScript, widely
 *   used, and tells the line of each element and of each syntax error.
 * - Path data goes through `svgpath` rather than a hand-written parser. We chose
 *   it over `svg-pathdata` because it also parses the `transform` attribute's
 *   grammar (matrix, translate, scale, rotate, skewX, skewY) and applies it to the
 *   path exactly, arcs included (the affine image of an ellipse arc is an ellipse
 *   arc: it maps the radii and the rotation and flips the sweep when the transform
 *   mirrors). So every curve is flattened once, in mm, against the chord tolerance
 *   itself, with no arc-to-cubic approximation eating into it. It is small, has no
 *   dependencies and ships its types.
 *
 * Every shape (rect, circle, ellipse, line, polyline, polygon) is written as path
 * data and goes the same way. A group's transforms apply innermost first, then the
 * root's viewBox and units (svgUnits.ts).
 *
 * A `<use>` (Inkscape's clones, symbols from a library) draws the element its href
 * names as if it sat in a group with the use's transform then translate(x, y), as
 * SVG renders it; a `<symbol>` without a viewBox draws as a group.
 */
import { DOMParser, type Element as XmlElement, type Node as XmlNode } from '@xmldom/xmldom';
import svgpath from 'svgpath';
import { DEFAULT_CHORD_TOLERANCE_MM, flattenCenterArc, flattenCubic, flattenQuadratic, svgArcToCenter } from './flatten.ts';
import { FileImportError, pathFromPoints, type Drawing, type FileWarning, type PlotPath } from './paths.ts';
import { lengthInPx, parseNumberList, rootMatrix } from './svgUnits.ts';

const SVG_NS = 'http://www.w3.org/2000/svg';
const XLINK_NS = 'http://www.w3.org/1999/xlink';

/** Elements never drawn, with all they contain. */
const NOT_RENDERED = new Set(['defs', 'symbol', 'clipPath', 'mask', 'marker', 'pattern', 'linearGradient', 'radialGradient', 'filter', 'style', 'script', 'title', 'desc', 'metadata']);
/** Drawable elements this importer does not draw: each is named in a warning. */
const NOT_SUPPORTED = new Set(['text', 'image', 'foreignObject', 'svg']);
const CONTAINERS = new Set(['g', 'a', 'switch']);
const SHAPES = new Set(['path', 'rect', 'circle', 'ellipse', 'line', 'polyline', 'polygon']);

export interface SvgImportOptions {
  /** mm, the greatest distance between a curve and its chords. */
  chordTolerance_mm?: number;
}

export function importSvg(name: string, text: string, options: SvgImportOptions = {}): Drawing {
  const tol = options.chordTolerance_mm ?? DEFAULT_CHORD_TOLERANCE_MM;
  if (!(tol > 0)) throw new FileImportError(`the chord tolerance must be > 0 mm, got ${tol}`);
  const root = parseXml(text);
  if (root.localName !== 'svg') throw new FileImportError(`this is not an SVG file: its root element is <${root.nodeName}>, not <svg>`, lineOf(root));
  const viewBoxText = root.getAttribute('viewBox');
  let viewBox: number[] | null = null;
  if (viewBoxText !== null && viewBoxText.trim() !== '') {
    viewBox = parseNumberList(viewBoxText);
    if (!viewBox || viewBox.length !== 4 || !(viewBox[2] > 0) || !(viewBox[3] > 0)) {
      throw new FileImportError(`<svg> has a bad viewBox "${viewBoxText}": it must be four numbers, min-x min-y width height, with width and height > 0`, lineOf(root));
    }
  }
  const page = rootMatrix(root.getAttribute('width'), root.getAttribute('height'), viewBox, root.getAttribute('preserveAspectRatio'));
  const walker = new Walker(tol, page.matrix, root);
  walker.children(root, [], true);
  if (walker.paths.length === 0) {
    const notDrawn = walker.warnings.length > 0 ? ` (${walker.warnings.map((w) => w.message).join('; ')})` : '';
    throw new FileImportError(`the file has no drawable geometry: no visible path, line, polyline, polygon, rect, circle or ellipse outside <defs>${notDrawn}`);
  }
  return { name, kind: 'svg', paths: walker.paths, warnings: walker.warnings };
}

function parseXml(text: string): XmlElement {
  let problem: { message: string; line?: number } | null = null;
  const parser = new DOMParser({
    onError: (level, message, context) => {
      if (level === 'warning' || problem) return;
      const line = (context as { locator?: { lineNumber?: number } } | undefined)?.locator?.lineNumber;
      problem = { message: String(message).split('\n')[0], line: line && line > 0 ? line : undefined };
    },
  });
  let doc;
  try {
    doc = parser.parseFromString(text, 'image/svg+xml');
  } catch (err) {
    const locator = (err as { locator?: { lineNumber?: number } }).locator;
    const line = locator?.lineNumber && locator.lineNumber > 0 ? locator.lineNumber : undefined;
    const message = err instanceof Error ? err.message : String(err);
    if (text.trim() === '') throw new FileImportError('the file is empty');
    throw new FileImportError(`the XML is malformed: ${message}`, line);
  }
  const found = problem as { message: string; line?: number } | null;
  if (found) throw new FileImportError(`the XML is malformed: ${found.message}`, found.line);
  if (!doc.documentElement) throw new FileImportError('the file has no root element');
  return doc.documentElement;
}

function lineOf(node: XmlNode): number | undefined {
  const n = (node as unknown as { lineNumber?: number }).lineNumber;
  return n && n > 0 ? n : undefined;
}

/** "<circle id="c1">" or "<circle>", for messages. */
function describe(el: XmlElement): string {
  const id = el.getAttribute('id');
  return id ? `<${el.localName} id="${id}">` : `<${el.localName}>`;
}

/** A presentation property from the attribute or the inline style (the style wins, as in CSS). */
function property(el: XmlElement, name: string): string | null {
  const style = el.getAttribute('style');
  if (style) {
    for (const decl of style.split(';')) {
      const i = decl.indexOf(':');
      if (i > 0 && decl.slice(0, i).trim() === name) return decl.slice(i + 1).replace(/!important/, '').trim();
    }
  }
  const attr = el.getAttribute(name);
  return attr === null ? null : attr.trim();
}

class Walker {
  readonly paths: PlotPath[] = [];
  readonly warnings: FileWarning[] = [];

  /** The elements a <use> being drawn refers to, to refuse a loop. */
  private readonly using = new Set<XmlElement>();
  /** Elements by id, gathered at the first <use>. */
  private ids: Map<string, XmlElement> | null = null;

  constructor(
    private readonly tol: number,
    private readonly page: [number, number, number, number, number, number],
    private readonly root: XmlElement,
  ) {}

  /** Walks `parent`'s element children; `transforms` are the ancestors' own, outermost first. */
  children(parent: XmlElement, transforms: readonly string[], visible: boolean): void {
    for (let node = parent.firstChild; node; node = node.nextSibling) {
      if (node.nodeType !== 1) continue;
      this.element(node as XmlElement, transforms, visible);
    }
  }

  private element(el: XmlElement, transforms: readonly string[], inheritedVisible: boolean): void {
    // Other vocabularies (Inkscape's sodipodi:namedview, …) carry no geometry.
    if (el.namespaceURI !== null && el.namespaceURI !== SVG_NS) return;
    const tag = el.localName ?? el.nodeName;
    if (NOT_RENDERED.has(tag)) return;
    if (property(el, 'display') === 'none') return;
    const visibility = property(el, 'visibility');
    const visible = visibility === 'hidden' || visibility === 'collapse' ? false : visibility === 'visible' ? true : inheritedVisible;
    const own = el.getAttribute('transform');
    const chain = own && own.trim() !== '' ? [...transforms, own] : transforms;
    if (CONTAINERS.has(tag)) {
      this.children(el, chain, visible);
      return;
    }
    if (tag === 'use') {
      this.use(el, chain, visible);
      return;
    }
    if (NOT_SUPPORTED.has(tag)) {
      if (visible) this.warnings.push({ line: lineOf(el), message: `${describe(el)} is not drawn: only path, line, polyline, polygon, rect, circle and ellipse are` });
      return;
    }
    if (!SHAPES.has(tag) || !visible) return;
    const d = shapeData(el, tag, this.warnings);
    if (d === null) return;
    this.draw(el, d, chain);
  }

  /** A <use>: the element it refers to, in a group moved by the use's transform (in `chain`) then its x, y. */
  private use(el: XmlElement, chain: readonly string[], visible: boolean): void {
    const href = (el.getAttribute('href') ?? el.getAttributeNS(XLINK_NS, 'href') ?? '').trim();
    const skip = (why: string) => {
      if (visible) this.warnings.push({ line: lineOf(el), message: `${describe(el)} is not drawn: ${why}` });
    };
    if (href === '') return skip('it has no href');
    if (!href.startsWith('#')) return skip(`it refers to "${href}", outside this file`);
    this.ids ??= idsUnder(this.root);
    const target = this.ids.get(href.slice(1));
    if (!target) return skip(`it refers to "${href}", and no element has that id`);
    let loop = this.using.has(target);
    for (let a: XmlNode | null = el; a && !loop; a = a.parentNode) loop = a === target;
    if (loop) throw new FileImportError(`${describe(el)} refers to "${href}", which contains it: the copies would never end`, lineOf(el));
    const x = num(el, 'x', 0) as number, y = num(el, 'y', 0) as number;
    const inner = x !== 0 || y !== 0 ? [...chain, `translate(${x} ${y})`] : chain;
    this.using.add(target);
    try {
      if (target.localName === 'symbol') {
        if (target.getAttribute('viewBox')) return skip('it refers to a <symbol> with its own viewBox, which this importer does not scale');
        this.children(target, inner, visible);
      } else this.element(target, inner, visible);
    } finally {
      this.using.delete(target);
    }
  }

  private draw(el: XmlElement, d: string, chain: readonly string[]): void {
    let p = svgpath(d);
    const err = (p as unknown as { err: string }).err;
    if (err) throw new FileImportError(`${describe(el)} has bad path data: ${err.replace(/^SvgPath: /, '')}`, lineOf(el));
    for (let i = chain.length - 1; i >= 0; i--) {
      if (!/^[\s,]*((matrix|translate|scale|rotate|skewX|skewY)\s*\([^)]*\)[\s,]*)*$/.test(chain[i])) {
        throw new FileImportError(`${describe(el)} (or a group around it) has a bad transform "${chain[i]}"`, lineOf(el));
      }
      p = p.transform(chain[i]);
    }
    p = p.matrix(this.page).abs().unshort();
    const before = this.paths.length;
    flattenPathData(p, this.tol, this.paths);
    const line = lineOf(el) ?? 0;
    for (let i = before; i < this.paths.length; i++) {
      const path = this.paths[i];
      for (const v of path.points) {
        if (!Number.isFinite(v)) throw new FileImportError(`${describe(el)} has coordinates that are not finite numbers`, lineOf(el));
      }
      // Every segment of the element's paths comes from its line.
      if (line > 0) path.lines = new Int32Array(path.points.length / 2 - 1).fill(line);
    }
  }
}

/** Every element under `root` (itself included) by its id; the first in document order wins. */
function idsUnder(root: XmlElement): Map<string, XmlElement> {
  const ids = new Map<string, XmlElement>();
  const visit = (el: XmlElement) => {
    const id = el.getAttribute('id');
    if (id && !ids.has(id)) ids.set(id, el);
    for (let node = el.firstChild; node; node = node.nextSibling) if (node.nodeType === 1) visit(node as XmlElement);
  };
  visit(root);
  return ids;
}

/** A number attribute in user units (lengths with units converted), `fallback` when absent. */
function num(el: XmlElement, name: string, fallback: number | null): number | null {
  const text = el.getAttribute(name);
  if (text === null || text.trim() === '' || text.trim() === 'auto') return fallback;
  const v = lengthInPx(text);
  if (v === null) throw new FileImportError(`${describe(el)} has ${name}="${text}", which is not a length this importer reads (a number, or one in mm, cm, in, px, pt or pc)`, lineOf(el));
  return v;
}

function need(el: XmlElement, name: string): number {
  const v = num(el, name, null);
  if (v === null) throw new FileImportError(`${describe(el)} has no ${name}`, lineOf(el));
  return v;
}

/** The element as path data, or null (with a warning) when it draws nothing. */
function shapeData(el: XmlElement, tag: string, warnings: FileWarning[]): string | null {
  const nothing = (why: string) => {
    warnings.push({ line: lineOf(el), message: `${describe(el)} draws nothing: ${why}` });
    return null;
  };
  switch (tag) {
    case 'path': {
      const d = el.getAttribute('d');
      if (d === null || d.trim() === '') return nothing('it has no d');
      return d;
    }
    case 'line': {
      const x1 = num(el, 'x1', 0) as number, y1 = num(el, 'y1', 0) as number;
      const x2 = num(el, 'x2', 0) as number, y2 = num(el, 'y2', 0) as number;
      return `M${x1} ${y1}L${x2} ${y2}`;
    }
    case 'polyline':
    case 'polygon': {
      const text = el.getAttribute('points') ?? '';
      const v = parseNumberList(text);
      if (v === null || v.length % 2 !== 0) throw new FileImportError(`${describe(el)} has bad points "${text.slice(0, 60)}": they must be pairs of numbers`, lineOf(el));
      if (v.length < 4) return nothing('it has fewer than two points');
      let d = `M${v[0]} ${v[1]}`;
      for (let i = 2; i < v.length; i += 2) d += `L${v[i]} ${v[i + 1]}`;
      return tag === 'polygon' ? d + 'Z' : d;
    }
    case 'rect': {
      const x = num(el, 'x', 0) as number, y = num(el, 'y', 0) as number;
      const w = need(el, 'width'), h = need(el, 'height');
      if (w < 0 || h < 0) throw new FileImportError(`${describe(el)} has a negative width or height`, lineOf(el));
      if (w === 0 || h === 0) return nothing('its width or height is 0');
      // SVG 2: an absent (or auto) rx takes ry's value and the other way round; each at most half the side.
      let rx = num(el, 'rx', null), ry = num(el, 'ry', null);
      if (rx === null) rx = ry ?? 0;
      if (ry === null) ry = rx;
      rx = Math.min(Math.max(0, rx), w / 2);
      ry = Math.min(Math.max(0, ry), h / 2);
      if (rx === 0 || ry === 0) return `M${x} ${y}H${x + w}V${y + h}H${x}Z`;
      return (
        `M${x + rx} ${y}H${x + w - rx}A${rx} ${ry} 0 0 1 ${x + w} ${y + ry}` +
        `V${y + h - ry}A${rx} ${ry} 0 0 1 ${x + w - rx} ${y + h}` +
        `H${x + rx}A${rx} ${ry} 0 0 1 ${x} ${y + h - ry}` +
        `V${y + ry}A${rx} ${ry} 0 0 1 ${x + rx} ${y}Z`
      );
    }
    case 'circle': {
      const cx = num(el, 'cx', 0) as number, cy = num(el, 'cy', 0) as number, r = need(el, 'r');
      if (r < 0) throw new FileImportError(`${describe(el)} has a negative r`, lineOf(el));
      if (r === 0) return nothing('its r is 0');
      return `M${cx + r} ${cy}A${r} ${r} 0 0 1 ${cx - r} ${cy}A${r} ${r} 0 0 1 ${cx + r} ${cy}Z`;
    }
    case 'ellipse': {
      const cx = num(el, 'cx', 0) as number, cy = num(el, 'cy', 0) as number;
      let rx = num(el, 'rx', null), ry = num(el, 'ry', null);
      if (rx === null) rx = ry;
      if (ry === null) ry = rx;
      if (rx === null || ry === null) throw new FileImportError(`${describe(el)} has no rx or ry`, lineOf(el));
      if (rx < 0 || ry < 0) throw new FileImportError(`${describe(el)} has a negative rx or ry`, lineOf(el));
      if (rx === 0 || ry === 0) return nothing('its rx or ry is 0');
      return `M${cx + rx} ${cy}A${rx} ${ry} 0 0 1 ${cx - rx} ${cy}A${rx} ${ry} 0 0 1 ${cx + rx} ${cy}Z`;
    }
  }
  return null;
}

/**
 * Absolute path data (M L H V C Q A Z; S and T already made C and Q) to polylines,
 * one per subpath, curves within `tol`.
 */
function flattenPathData(p: ReturnType<typeof svgpath>, tol: number, out: PlotPath[]): void {
  let pts: number[] = [];
  let startX = 0, startY = 0;
  const flush = () => {
    if (pts.length >= 4) out.push(pathFromPoints(pts));
    pts = [];
  };
  p.iterate((s, _index, x, y) => {
    const cmd = s[0];
    if (cmd !== 'M' && pts.length === 0) pts.push(x, y);
    switch (cmd) {
      case 'M':
        flush();
        pts.push(s[1], s[2]);
        startX = s[1];
        startY = s[2];
        break;
      case 'L':
        pts.push(s[1], s[2]);
        break;
      case 'H':
        pts.push(s[1], y);
        break;
      case 'V':
        pts.push(x, s[1]);
        break;
      case 'C':
        flattenCubic(pts, x, y, s[1], s[2], s[3], s[4], s[5], s[6], tol);
        break;
      case 'Q':
        flattenQuadratic(pts, x, y, s[1], s[2], s[3], s[4], tol);
        break;
      case 'A': {
        // svgpath may hand flags back as '0'/'1' strings after a mirroring transform.
        const arc = svgArcToCenter(x, y, s[1], s[2], s[3], Number(s[4]) !== 0, Number(s[5]) !== 0, s[6], s[7]);
        if (arc) flattenCenterArc(pts, arc, tol, [s[6], s[7]]);
        else pts.push(s[6], s[7]);
        break;
      }
      case 'Z':
      case 'z':
        if (pts[pts.length - 2] !== startX || pts[pts.length - 1] !== startY) pts.push(startX, startY);
        flush();
        break;
    }
  });
  flush();
}
