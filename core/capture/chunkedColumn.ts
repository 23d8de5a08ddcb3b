/**
 * A column of numbers that grows by whole chunks (Float64Array of CHUNK each): adding a
 * sample never copies the ones before it, however long the capture (600 000 samples for
 * 10 minutes at 1 kHz). A doubling array would copy everything at each doubling, and
 * hold up to twice what it needs.
 *
 * Reading it whole (`toArray`) makes one contiguous copy, kept until the next push, so
 * asking again costs nothing.
 */
export const CHUNK = 16_384;

export class ChunkedColumn {
  private readonly chunks: Float64Array[] = [];
  private count = 0;
  private whole: Float64Array | null = null;

  get length(): number {
    return this.count;
  }

  push(value: number): void {
    const at = this.count % CHUNK;
    if (at === 0) this.chunks.push(new Float64Array(CHUNK));
    this.chunks[this.chunks.length - 1][at] = value;
    this.count++;
    this.whole = null;
  }

  /** The value at k (0 ≤ k < length). */
  get(k: number): number {
    if (!(k >= 0 && k < this.count)) throw new RangeError(`index ${k} is outside the column (it holds ${this.count})`);
    return this.chunks[Math.floor(k / CHUNK)][k % CHUNK];
  }

  /** Values [from, to) into `out` at `at`. */
  copyInto(out: Float64Array, from = 0, to = this.count, at = 0): Float64Array {
    if (!(from >= 0 && from <= to && to <= this.count)) throw new RangeError(`range [${from}, ${to}) is outside the column (it holds ${this.count})`);
    let k = from;
    while (k < to) {
      const chunk = this.chunks[Math.floor(k / CHUNK)];
      const start = k % CHUNK;
      const n = Math.min(CHUNK - start, to - k);
      out.set(chunk.subarray(start, start + n), at + k - from);
      k += n;
    }
    return out;
  }

  /** Every value, contiguous: one copy, the same array until the next push. */
  toArray(): Float64Array {
    this.whole ??= this.copyInto(new Float64Array(this.count));
    return this.whole;
  }
}
