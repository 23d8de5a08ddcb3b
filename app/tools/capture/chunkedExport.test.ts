/**
 * The sliced export: every piece once and in order, the page given its turn between
 * slices, progress rising to the whole, and a cancel that keeps nothing.
 */
import { describe, expect, it } from 'vitest';
import { exportInSlices } from './chunkedExport.ts';

function* pieces(rows: number, perPiece: number, workMs = 0): Generator<string> {
  yield 'header';
  for (let from = 0; from < rows; from += perPiece) {
    const end = performance.now() + workMs;
    while (performance.now() < end) {
      // a piece that takes workMs to make
    }
    yield `\n${Array.from({ length: Math.min(perPiece, rows - from) }, (_, k) => from + k).join('\n')}`;
  }
}

describe('exportInSlices', () => {
  it('joins every piece in order, in several slices with the page’s turn between, progress rising to the whole', async () => {
    const progress: number[] = [];
    let turns = 0;
    const ticker = setInterval(() => turns++, 0);
    const blob = await exportInSlices(pieces(1000, 30, 1), { perPiece: 30, total: 1000, sliceMs: 5, type: 'text/csv', onProgress: (done) => progress.push(done) });
    clearInterval(ticker);
    const text = await blob.text();
    expect(text).toBe(['header', ...Array.from({ length: 1000 }, (_, k) => k)].join('\n'));
    expect(blob.type).toBe('text/csv');
    expect(progress.length).toBeGreaterThan(3);
    for (let i = 1; i < progress.length; i++) expect(progress[i]).toBeGreaterThanOrEqual(progress[i - 1]);
    expect(progress[progress.length - 1]).toBe(1000);
    expect(turns).toBeGreaterThan(0);
  });

  it('an empty capture is its header; a cancel rejects', async () => {
    expect(await (await exportInSlices(pieces(0, 10), { perPiece: 10, total: 0, type: 'text/csv' })).text()).toBe('header');
    const abort = new AbortController();
    const run = exportInSlices(pieces(1000, 10, 1), { perPiece: 10, total: 1000, sliceMs: 2, type: 'text/csv', signal: abort.signal, onProgress: () => abort.abort() });
    await expect(run).rejects.toThrow(/cancelled/);
  });
});
