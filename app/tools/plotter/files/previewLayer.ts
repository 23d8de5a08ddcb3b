/**
 * What the file preview draws on the bed, in machine mm (x, y interleaved; x right,
 * y down the bed): a plain typed shape, so that any bed view can draw it as a layer
 * (its strokes and travel are polylines, as the plotter's BedView preview takes).
 */
export interface PreviewLayer {
  /** The pen-down paths, in plotting order. */
  strokes: Float64Array[];
  /** Pen-up travel as planned (after ordering): one [x0, y0, x1, y1] per move, from the pen's position. */
  travel: Float64Array[];
  /** Pen-up travel in the file's order, for comparison. */
  travelBefore: Float64Array[];
  /** mm, the area the drawing must fit in (the soft limits), or null if the machine has none. */
  area: { minX: number; minY: number; maxX: number; maxY: number } | null;
}

/** The travel moves from `start` to each stroke's first point, from the one before's last. */
export function travelLines(strokes: readonly { points: Float64Array }[], start: readonly [number, number]): Float64Array[] {
  let x = start[0], y = start[1];
  return strokes.map((s) => {
    const line = Float64Array.of(x, y, s.points[0], s.points[1]);
    x = s.points[s.points.length - 2];
    y = s.points[s.points.length - 1];
    return line;
  });
}

/** The buffers of a layer, for postMessage's transfer list. */
export function layerBuffers(l: PreviewLayer): ArrayBuffer[] {
  return [...l.strokes, ...l.travel, ...l.travelBefore].map((a) => a.buffer as ArrayBuffer);
}
