/** A Float32Array that grows by doubling, for collecting vertices between snapshots. */
export class GrowableFloats {
  private data = new Float32Array(1024);
  length = 0;

  push3(x: number, y: number, z: number): void {
    if (this.length + 3 > this.data.length) {
      const grown = new Float32Array(this.data.length * 2);
      grown.set(this.data);
      this.data = grown;
    }
    const d = this.data;
    d[this.length] = x;
    d[this.length + 1] = y;
    d[this.length + 2] = z;
    this.length += 3;
  }

  /** The values collected so far, as a new array of exactly that length, and starts again. */
  take(): Float32Array {
    const out = this.data.slice(0, this.length);
    this.length = 0;
    return out;
  }

  clear(): void {
    this.length = 0;
  }
}
