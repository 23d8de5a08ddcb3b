/**
 * The simulated pen's ink (the plant's pen-down strokes, core/sim/plant/penServo.ts)
 * as the plotter shows and saves it: from the last Clear on, and to the page
 * incrementally, each post carrying only the points not sent before, in
 * transferable Float32Arrays. Another simulated machine starts the ink afresh.
 */
import type { SimulatedMachine } from '../../../../core/sim/machine.ts';

export interface InkPiece {
  /** Which pen stroke (from the last clear), and the index of its first point here. */
  index: number;
  from: number;
  /** x, y pairs, mm. */
  xy: Float32Array;
}

export class SimulatedInk {
  /** The plant's pen strokes before this one are cleared. */
  private from = 0;
  /** Points of each stroke already posted. */
  private posted: number[] = [];
  private sim: SimulatedMachine | null = null;

  /** Follows `sim` (null on real boards); true if it is another machine than before (the ink starts afresh). */
  follow(sim: SimulatedMachine | null): boolean {
    if (sim === this.sim) return false;
    this.sim = sim;
    this.from = 0;
    this.posted = [];
    return true;
  }

  /** Forgets the ink so far: shown and saved ink start from the next stroke. */
  clear(): void {
    this.from = this.sim?.plant.pen?.strokes.length ?? 0;
    this.posted = [];
  }

  /** Every stroke since the clear, x, y pairs (null when no pen is simulated). With `times`, x, y, t_us triples. */
  strokes(times = false): number[][] | null {
    const pen = this.sim?.plant.pen;
    if (!pen) return null;
    this.sim?.sync();
    return pen.strokes.slice(this.from).map((s) => {
      const n = times ? 3 : 2;
      const out = new Array<number>(s.x.length * n);
      for (let i = 0; i < s.x.length; i++) {
        out[n * i] = s.x[i];
        out[n * i + 1] = s.y[i];
        if (times) out[n * i + 2] = s.t_us[i];
      }
      return out;
    });
  }

  /** The points added since the last call (each piece repeats the last point posted, so it joins the one before). */
  newPieces(): InkPiece[] {
    const pen = this.sim?.plant.pen;
    if (!pen) return [];
    const pieces: InkPiece[] = [];
    for (let i = this.from; i < pen.strokes.length; i++) {
      const s = pen.strokes[i];
      const k = i - this.from;
      const done = this.posted[k] ?? 0;
      if (s.x.length <= done) continue;
      const start = Math.max(0, done - 1);
      const xy = new Float32Array((s.x.length - start) * 2);
      for (let j = start; j < s.x.length; j++) {
        xy[2 * (j - start)] = s.x[j];
        xy[2 * (j - start) + 1] = s.y[j];
      }
      pieces.push({ index: k, from: start, xy });
      this.posted[k] = s.x.length;
    }
    return pieces;
  }
}
