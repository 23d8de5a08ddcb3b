/**
 * Incremental lookahead: the speed at every junction of a growing polyline.
 *
 * ## The problem
 * Blocks (straight segments) k = 0, 1, … are appended one by one. Block k has
 * length L_k, an acceleration limit a_k along its direction, a cruise cap and a cap
 * on its entry speed from the junction with block k − 1 (junction deviation and
 * both blocks' cruise caps): `maxEntry2`. We work in squared speeds, because at
 * constant acceleration a over a distance d, v² changes by exactly 2·a·d.
 *
 * Let e_k be the squared speed at junction k (the entry of block k). A plan is
 * feasible when, for every block k,
 *   (1) e_k ≤ cap_k                      (junction and cruise caps)
 *   (2) e_{k+1} ≤ e_k + 2·a_k·L_k         (it can speed up that much over block k)
 *   (3) e_k ≤ e_{k+1} + 2·a_k·L_k         (it can slow down that much over block k)
 * with e at the front fixed (rest, or the exit of the last locked block) and e = 0
 * at the end of the known path: the end always plans to rest, so the machine can
 * stop if nothing more arrives. The time-optimal plan takes every e_k as large as
 * the constraints allow; the largest feasible e_k is min(f_k, b_k), where
 *   b_k = the backward bound: the largest e_k from which every later junction's
 *         cap, and the final rest, can still be met by decelerating;
 *   f_k = the forward bound: the largest e_k reachable by accelerating from the
 *         front without breaking any b.
 * Within each block the speed then follows a trapezoid (see phases.ts), which is
 * time-optimal between given entry and exit speeds.
 *
 * ## The backward pass as a suffix minimum
 * Unrolling (1) and (3) backwards from junction j to junction k:
 *   b_k = min over j ≥ k of ( cap_j + 2·Σ_{k ≤ i < j} a_i·L_i ),   with cap_end = 0.
 * Write W_k = Σ_{i < k} a_i·L_i (the "work" prefix) and C_j = cap_j + 2·W_j. Then
 *   b_k = ( min over j ≥ k of C_j ) − 2·W_k.
 * So the backward pass is a suffix minimum of C. The end junction is special: its
 * C = 2·W_end (rest) rises when a block is appended, and that junction then turns
 * into an interior one whose C (its real cap) never changes again. So the interior
 * junctions live in a monotonic deque of suffix-minimum candidates (each with a
 * smaller C than every candidate after it), and the end's C is compared on the fly:
 *   b_k = min( min over interior j ≥ k of C_j,  2·W_end ) − 2·W_k.
 * An append pushes one interior junction, popping the candidates it dominates: each
 * junction is pushed once and popped at most once, so O(1) amortised. (Keeping the
 * end in the deque would be wrong: a rest value that pops candidates and later
 * rises would have lost them.) A GRBL-style backward pass that walks from the tail
 * to the planned pointer costs O(blocks within a braking distance) per append
 * instead; on a fine spiral that is ~50 blocks.
 *
 * ## The forward pass and the planned pointer
 *   f_{k+1} = min( b_{k+1}, f_k + 2·a_k·L_k ),   f_front = the fixed front speed.
 * The planned pointer marks how far this is final. f_{k+1} can never change again
 * once either
 *   - f_k + 2·a_k·L_k ≤ b_{k+1}: the block is acceleration limited, and later
 *     blocks only ever raise b; or
 *   - b_{k+1} is set by an interior junction's cap rather than by the end's rest:
 *     appends only raise the end's C (W grows) and add interior candidates after
 *     it whose C is at least the end's old value, so that minimum stays.
 * These are GRBL's two conditions (full acceleration, or an entry at its maximum)
 * read off the deque. Blocks behind the pointer are "planned": their speeds are
 * final and their profiles can be timed, evaluated and sent. Each block crosses
 * the pointer once, so the forward pass is O(1) amortised too.
 *
 * ## Locking
 * Transmitted blocks are locked: the executor takes the front block with
 * lockFront(). If the pointer has not reached it, its exit is decided with what is
 * known now (still stoppable, since e ≤ b), and that speed becomes the fixed entry
 * of the new front.
 */
import { shouldDropSpent } from './spentPrefix.ts';

export interface PlanBlock {
  /** mm */
  length: number;
  /** mm/s², the acceleration limit along this block's direction */
  accel: number;
  /** (mm/s)², the cruise cap inside this block */
  cruise2: number;
  /** (mm/s)², the cap on the entry speed²: junction deviation and both blocks' cruise caps */
  maxEntry2: number;
  /** (mm/s)², planned entry speed² (final once the block is behind the planned pointer) */
  entry2: number;
  /** (mm/s)², planned exit speed² */
  exit2: number;
  /** planner bookkeeping: W at this block's entry, Σ a·L over earlier unlocked blocks */
  work: number;
}

/** How a block's plan is reported to the owner when it becomes final. */
export type FinalListener<B> = (block: B) => void;

export class LookaheadPlanner<B extends PlanBlock> {
  /** Unlocked blocks; blocks[head] is the front. */
  private blocks: B[] = [];
  private head = 0;
  /** Absolute index of the front block (= number of blocks locked so far). */
  private first = 0;
  /** Squared speed at the front junction: 0 at rest, or the last locked block's exit. */
  private frontEntry2 = 0;
  /** W at the end junction. */
  private endWork = 0;
  /** Suffix-minimum candidates among interior junctions: indices (absolute) and C values. */
  private candJunction: number[] = [];
  private candValue: number[] = [];
  private candHead = 0;
  /** Blocks [front, front + plannedCount) have a final entry and exit. */
  private plannedCount = 0;
  /** Set by backwardBound(): whether the end-of-path rest set the bound it returned. */
  private boundSetByEnd = false;
  private readonly onFinal: FinalListener<B> | undefined;

  constructor(onFinal?: FinalListener<B>) {
    this.onFinal = onFinal;
  }

  /** Unlocked blocks held. */
  get size(): number {
    return this.blocks.length - this.head;
  }

  /** Unlocked blocks whose plan is final. */
  get plannedSize(): number {
    return this.plannedCount;
  }

  /** Squared speed at which the front block (or the next block appended, if none) starts. */
  get frontSpeed2(): number {
    return this.frontEntry2;
  }

  /** The i-th unlocked block, 0 being the front. */
  at(i: number): B {
    return this.blocks[this.head + i];
  }

  append(block: B): void {
    const count = this.size;
    const k = this.first + count;
    block.work = this.endWork;
    if (count === 0) {
      // The new block is the front: its entry is fixed, so junction k needs no candidate.
      block.entry2 = this.frontEntry2;
    } else {
      // Junction k was the end of the path, at rest; it is now interior, with its real cap.
      this.pushCandidate(k, block.maxEntry2 + 2 * block.work);
    }
    this.endWork = block.work + block.accel * block.length;
    this.blocks.push(block);
    this.advance(false);
  }

  /**
   * Finalises every block as if the path ended here, at rest. For a path known to
   * be complete (planPath), and before locking the last blocks of a finished job.
   */
  planToRest(): void {
    this.advance(true);
  }

  /**
   * Locks the front block for transmission and returns it. Its exit speed is final
   * from now on and becomes the entry speed of the next block.
   */
  lockFront(): B {
    const count = this.size;
    if (count === 0) throw new Error('lockFront: no unlocked block');
    const block = this.blocks[this.head];
    const decidedNow = this.plannedCount === 0;
    if (decidedNow) {
      // Not final yet: decide with what is known now (always stoppable: e ≤ b).
      const exit2 = this.frontExit2();
      block.exit2 = exit2;
      if (count > 1) this.blocks[this.head + 1].entry2 = exit2;
    } else {
      this.plannedCount--;
    }
    this.frontEntry2 = block.exit2;
    this.head++;
    this.first++;
    if (this.size === 0) this.reset();
    // Every operation leaves the planned pointer as far as it can go. Locking a front
    // that was already final changes neither the entry there nor any bound (W and C
    // are absolute), so the pointer stays; only an exit decided now, which fixes the
    // next block's entry, may let it move.
    else if (decidedNow) this.advance(false);
    this.compact();
    return block;
  }

  /** The exit speed² that lockFront() would give the front block now. */
  frontExit2(): number {
    const block = this.blocks[this.head];
    if (this.plannedCount > 0) return block.exit2;
    if (this.size === 1) return 0;
    return Math.min(this.backwardBound(this.first + 1, false), block.entry2 + 2 * block.accel * block.length);
  }

  /**
   * Removes every unlocked block from the i-th on (0 = the front) and returns them
   * in order. The remaining plan is recomputed from the front.
   */
  truncate(i: number): B[] {
    const removed = this.blocks.splice(this.head + i);
    this.rebuild();
    return removed;
  }

  /**
   * Removes every unlocked block and forgets the last locked exit: the next block
   * appended starts from rest (a job resumed after the machine stopped off its plan).
   */
  clearToRest(): B[] {
    const removed = this.truncate(0);
    this.frontEntry2 = 0;
    return removed;
  }

  /**
   * Whether the fixed front speed can still be honoured: it must not exceed the
   * front block's entry cap (after a replace changed the corner), and the machine
   * must still be able to come to rest by the end of the known path (after a
   * truncate removed path it needed for braking).
   */
  isFeasible(): boolean {
    const count = this.size;
    const e = this.frontEntry2;
    const slack = 1e-9 * (1 + e);
    if (count === 0) return e === 0;
    const front = this.blocks[this.head];
    if (e > front.maxEntry2 + slack) return false;
    const after = count === 1 ? 0 : this.backwardBound(this.first + 1, false);
    return e <= after + 2 * front.accel * front.length + slack;
  }

  /**
   * Fills entry2/exit2 of the blocks beyond the planned pointer with the plan as it
   * stands (ending at rest). These values are provisional: more blocks may raise
   * them. For display only; it changes nothing that is final. O(unplanned blocks).
   */
  fillProvisional(): void {
    const start = this.head + this.plannedCount;
    const end = this.blocks.length;
    if (start >= end) return;
    // Backward pass from the end at rest: exit2 holds b of the following junction.
    let next2 = 0;
    for (let k = end - 1; k > start; k--) {
      const b = this.blocks[k];
      b.exit2 = next2;
      next2 = Math.min(b.maxEntry2, next2 + 2 * b.accel * b.length);
    }
    this.blocks[start].exit2 = next2;
    // Forward pass from the pointer's final entry.
    let entry2 = this.blocks[start].entry2;
    for (let k = start; k < end; k++) {
      const b = this.blocks[k];
      b.entry2 = entry2;
      const exit2 = Math.min(b.exit2, entry2 + 2 * b.accel * b.length);
      b.exit2 = exit2;
      entry2 = exit2;
    }
  }

  // --- internals ---

  private pushCandidate(junction: number, value: number): void {
    const js = this.candJunction;
    const vs = this.candValue;
    while (vs.length > this.candHead && vs[vs.length - 1] > value) {
      vs.pop();
      js.pop();
    }
    js.push(junction);
    vs.push(value);
  }

  private workAt(junction: number): number {
    const i = junction - this.first;
    return i < this.size ? this.blocks[this.head + i].work : this.endWork;
  }

  /**
   * b at a junction: min(later interior candidates' C, the end's 2·W_end) − 2·W.
   * `consume` drops the candidates before it, which the forward pass (monotone)
   * never needs again. Leaves in boundSetByEnd whether the end-of-path rest sets
   * the minimum (then more blocks may raise it).
   */
  private backwardBound(junction: number, consume = true): number {
    const js = this.candJunction;
    let h = this.candHead;
    while (h < js.length && js[h] < junction) h++;
    if (consume) this.candHead = h;
    const interior = h < js.length ? this.candValue[h] : Infinity;
    const end = 2 * this.endWork;
    this.boundSetByEnd = end < interior;
    return Math.min(interior, end) - 2 * this.workAt(junction);
  }

  /** Moves the planned pointer forward as far as the plan is final. */
  private advance(toRest: boolean): void {
    const end = this.blocks.length;
    let p = this.head + this.plannedCount;
    while (p < end) {
      const block = this.blocks[p];
      const reach2 = block.entry2 + 2 * block.accel * block.length;
      let exit2: number;
      if (p + 1 === end) {
        if (!toRest) break;
        exit2 = 0;
      } else {
        const bound = this.backwardBound(this.first + (p + 1 - this.head));
        if (this.boundSetByEnd && reach2 > bound && !toRest) break;
        exit2 = Math.min(bound, reach2);
        this.blocks[p + 1].entry2 = exit2;
      }
      block.exit2 = exit2;
      this.plannedCount++;
      p++;
      this.onFinal?.(block);
    }
  }

  private reset(): void {
    this.blocks = [];
    this.head = 0;
    this.candJunction = [];
    this.candValue = [];
    this.candHead = 0;
    this.plannedCount = 0;
    this.endWork = 0;
  }

  /** Recomputes the work prefix, the candidates and the forward pass from the front. */
  private rebuild(): void {
    const kept = this.blocks.slice(this.head);
    this.reset();
    for (const block of kept) this.append(block);
  }

  private compact(): void {
    if (shouldDropSpent(this.head, this.blocks.length)) {
      this.blocks = this.blocks.slice(this.head);
      this.head = 0;
    }
    if (shouldDropSpent(this.candHead, this.candJunction.length)) {
      this.candJunction = this.candJunction.slice(this.candHead);
      this.candValue = this.candValue.slice(this.candHead);
      this.candHead = 0;
    }
  }
}
