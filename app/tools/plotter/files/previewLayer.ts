/**
 * What the file preview draws on the bed, in machine mm (x, y interleaved; x right,
 * y down the bed), packed in a few flat buffers: a plain typed shape that any bed
 * view can draw as a layer.
 *
 * Packed, not one array per path: a vpype or Inkscape file of 20 000 short paths
 * made 60 000 typed arrays per preview, and taking them from the worker's message
 * and laying them out as as many SVG elements froze the page for over a second on
 * every setting changed. Four buffers cross in no time, and the preview draws them
 * on a canvas.
 */

/** Polylines in one buffer: polyline i is the points from ends[i − 1] (0 for the first) to ends[i], exclusive. */
export interface PackedLines {
  /** x, y pairs, mm. */
  xy: Float64Array;
  /** Point index (not coordinate index) after each polyline's last point. */
  ends: Uint32Array;
}

export interface PreviewLayer {
  /** The pen-down paths, in plotting order. */
  strokes: PackedLines;
  /** Pen-up travel as planned (after ordering): x0, y0, x1, y1 per move, from the pen's position. */
  travel: Float64Array;
  /** Pen-up travel in the file's order, for comparison; as `travel`. */
  travelBefore: Float64Array;
  /** mm, the area the drawing must fit in (the soft limits), or null if the machine has none. */
  area: { minX: number; minY: number; maxX: number; maxY: number } | null;
}

export function packLines(lines: readonly { points: Float64Array }[]): PackedLines {
  let total = 0;
  for (const l of lines) total += l.points.length;
  const xy = new Float64Array(total);
  const ends = new Uint32Array(lines.length);
  let at = 0;
  lines.forEach((l, i) => {
    xy.set(l.points, at);
    at += l.points.length;
    ends[i] = at / 2;
  });
  return { xy, ends };
}

/** The travel moves from `start` to each stroke's first point, from the one before's last: x0, y0, x1, y1 each. */
export function travelLines(strokes: readonly { points: Float64Array }[], start: readonly [number, number]): Float64Array {
  const out = new Float64Array(4 * strokes.length);
  let x = start[0], y = start[1];
  strokes.forEach((s, i) => {
    out.set([x, y, s.points[0], s.points[1]], 4 * i);
    x = s.points[s.points.length - 2];
    y = s.points[s.points.length - 1];
  });
  return out;
}

/** The buffers of a layer, for postMessage's transfer list. */
export function layerBuffers(l: PreviewLayer): ArrayBuffer[] {
  return [l.strokes.xy, l.strokes.ends, l.travel, l.travelBefore].map((a) => a.buffer as ArrayBuffer);
}
