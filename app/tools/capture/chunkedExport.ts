/**
 * A long export built on the page without freezing it: the pieces of a text (a
 * 600 000-row CSV) are taken a time slice at a time, the page gets its turn between
 * slices (a redraw, a click), and each slice reports how far it got.
 *
 * A slice takes pieces until `sliceMs` have passed: with pieces of a few ms each, no
 * task of the export runs much over sliceMs + one piece.
 */

export interface ChunkedExportOptions {
  /** how much of the whole each piece is (rows), for the progress */
  perPiece: number;
  /** the whole (rows) */
  total: number;
  /** told after each slice: the part done (rows) and the whole */
  onProgress?: (done: number, total: number) => void;
  /** work per slice before the page gets its turn, ms (default 12) */
  sliceMs?: number;
  signal?: AbortSignal;
  /** the MIME type of the result */
  type: string;
}

/** The page's turn: a macrotask, so input, rendering and other tasks run first. */
const yieldToPage = () => new Promise<void>((resolve) => setTimeout(resolve, 0));

/** Takes every piece of `pieces`, slice by slice, into one Blob. Rejects (keeping nothing) if `signal` aborts. */
export async function exportInSlices(pieces: Iterator<string>, options: ChunkedExportOptions): Promise<Blob> {
  const sliceMs = options.sliceMs ?? 12;
  const parts: string[] = [];
  let done = 0;
  for (;;) {
    const start = performance.now();
    let finished = false;
    while (performance.now() - start < sliceMs) {
      const next = pieces.next();
      if (next.done) {
        finished = true;
        break;
      }
      parts.push(next.value);
      // The first piece is the header; each one after it holds perPiece rows (the last maybe fewer).
      if (parts.length > 1) done = Math.min(options.total, done + options.perPiece);
    }
    options.onProgress?.(finished ? options.total : done, options.total);
    if (finished) return new Blob(parts, { type: options.type });
    await yieldToPage();
    if (options.signal?.aborted) throw new Error('the export was cancelled');
  }
}
