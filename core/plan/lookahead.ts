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
 *
 * ## How deep the lookahead must be
 * The front block's exit is final (the planned pointer has passed it) exactly when
 * its bound no longer depends on the end of the known path: when the path known
 * after it is long enough to brake from the speed it can reach there. So an owner
 * that locks only final blocks, and keeps appending while none is final
 * (`needsMorePath`), plans exactly what planPath plans for the whole path, however
 * short the blocks: the depth is a braking distance, not a count of blocks.
 *
 * ## The store
 * Blocks are numbers only, kept in a ring: one Float64Array of records, six numbers
 * a block side by side (length, accel, maxEntry2, entry2, exit2 and work, 48 bytes),
 * rather than a column per quantity, because the blocks worked on are at the ring's
 * two ends (appended at one, planned and locked at the other, thousands of blocks
 * apart at a deep lookahead, out of the cache) and a record is one cache line where
 * six columns are six. Block k (absolute: counted since the planner was made) lives
 * at slot k & mask. The ring doubles when full, so it holds as many blocks as braking needs
 * without a fixed count, and allocates nothing per block. The candidate deque is a
 * second ring of the same capacity (junction and C side by side): its junctions all lie strictly inside the
 * unlocked blocks (lockFront drops the one at the front junction), so it never
 * holds more entries than there are blocks. The owner keeps its own objects for the
 * blocks (the queue's segments) and hears of each final plan by offset from the
 * front (onFinal).
 */
/** The planner inputs of one block (see the module comment). */
export interface BlockLimits {
  /** mm */
  length: number;
  /** mm/s², the acceleration limit along this block's direction */
  accel: number;
  /** (mm/s)², the cap on the entry speed²: junction deviation and both blocks' cruise caps */
  maxEntry2: number;
}

/**
 * Told, in path order, of each block whose plan became final: its offset from the
 * front block at that moment (0 = the front). Its entry and exit speeds² are
 * finalEntry2(offset) and finalExit2(offset): only the offset, an integer, is
 * passed, as a double argument to a call the engine does not inline is a number
 * allocated on the heap, a million a second here.
 */
export type FinalListener = (offset: number) => void;

/** Told of each unplanned block's provisional speeds (fillProvisional). */
export type ProvisionalListener = (offset: number, entry2: number, exit2: number) => void;

const INITIAL_CAPACITY = 1024;
/**
 * A block's numbers, side by side (see "The store"): its inputs (length, mm;
 * acceleration limit, mm/s²; entry cap, mm²/s²), its entry and exit speeds², and W
 * at its entry: Σ a·L over the unlocked blocks before it (since the last reset).
 */
const LENGTH = 0;
const ACCEL = 1;
const MAX_ENTRY2 = 2;
const ENTRY2 = 3;
const EXIT2 = 4;
const WORK = 5;
const BLOCK_STRIDE = 6;
/** The largest store made up front (48 MB); more blocks than that grow it as they come. */
const MAX_INITIAL_CAPACITY = 1 << 20;

export class LookaheadPlanner {
  // --- the block ring: block k at slot k & mask, its numbers at blocks[slot · BLOCK_STRIDE + field] ---
  private mask = INITIAL_CAPACITY - 1;
  private blocks = new Float64Array(INITIAL_CAPACITY * BLOCK_STRIDE);
  /** Absolute index of the front block (= blocks locked so far). */
  private first = 0;
  /** Absolute index one past the last block. */
  private end = 0;
  /** Blocks [first, first + plannedCount) have a final entry and exit. */
  private plannedCount = 0;
  /**
   * The two numbers below, kept in a Float64Array rather than as fields: both are
   * written for every block, and a profile of the planner bench found each such field
   * write allocating a heap number (the engine had not kept the field unboxed).
   */
  private readonly scalars = new Float64Array(2);
  /** Squared speed at the front junction: 0 at rest, or the last locked block's exit. */
  private get frontEntry2(): number {
    return this.scalars[0];
  }
  private set frontEntry2(v: number) {
    this.scalars[0] = v;
  }
  /** W at the end junction. */
  private get endWork(): number {
    return this.scalars[1];
  }
  private set endWork(v: number) {
    this.scalars[1] = v;
  }

  // --- the suffix-minimum candidates: absolute junction indices and C values, entries [candHead, candTail) at slot & mask ---
  private cands = new Float64Array(INITIAL_CAPACITY * 2);
  private candHead = 0;
  private candTail = 0;
  /** Set by backwardBound(): whether the end-of-path rest set the bound it returned. */
  private boundSetByEnd = false;
  private readonly onFinal: FinalListener | undefined;

  /** `expected`: how many blocks the planner will hold at once, if known (planPath: all); the store grows past it anyway. */
  constructor(expected: number, onFinal?: FinalListener) {
    this.onFinal = onFinal;
    const wanted = Number.isFinite(expected) ? Math.min(Math.max(INITIAL_CAPACITY, expected), MAX_INITIAL_CAPACITY) : INITIAL_CAPACITY;
    const capacity = 2 ** Math.ceil(Math.log2(wanted));
    if (capacity !== INITIAL_CAPACITY) this.resize(capacity);
  }

  /** Unlocked blocks held. */
  get size(): number {
    return this.end - this.first;
  }

  /** Unlocked blocks whose plan is final. */
  get plannedSize(): number {
    return this.plannedCount;
  }

  /**
   * Whether the front block's exit still depends on path not yet given: the known
   * path after it is shorter than braking from the speed it may reach needs (or
   * there is no block). An owner that wants the time-optimal plan appends while
   * this holds, and locks only once it does not.
   */
  get needsMorePath(): boolean {
    return this.plannedCount === 0;
  }

  /** Whether the plan of the block `offset` places after the front (0 = the front) is final. */
  isFinal(offset: number): boolean {
    return offset < this.plannedCount;
  }

  /** The final entry speed² of the block `offset` places after the front; meaningful only while isFinal(offset). */
  finalEntry2(offset: number): number {
    return this.blocks[((this.first + offset) & this.mask) * BLOCK_STRIDE + ENTRY2];
  }

  /** The final exit speed² of the block `offset` places after the front; meaningful only while isFinal(offset). */
  finalExit2(offset: number): number {
    return this.blocks[((this.first + offset) & this.mask) * BLOCK_STRIDE + EXIT2];
  }

  /** The length (mm) given for the block `offset` places after the front. */
  lengthAt(offset: number): number {
    return this.blocks[((this.first + offset) & this.mask) * BLOCK_STRIDE + LENGTH];
  }

  /** The acceleration limit (mm/s²) given for the block `offset` places after the front. */
  accelAt(offset: number): number {
    return this.blocks[((this.first + offset) & this.mask) * BLOCK_STRIDE + ACCEL];
  }

  /** The entry cap (mm²/s²) given for the block `offset` places after the front. */
  maxEntry2At(offset: number): number {
    return this.blocks[((this.first + offset) & this.mask) * BLOCK_STRIDE + MAX_ENTRY2];
  }

  /** Squared speed at which the front block (or the next block appended, if none) starts. */
  get frontSpeed2(): number {
    return this.frontEntry2;
  }

  /** Appends a block at the end of the path: its length (mm), acceleration limit (mm/s²) and entry cap (mm²/s²). */
  append(length: number, accel: number, maxEntry2: number): void {
    if (this.end - this.first > this.mask) this.grow();
    const k = this.end;
    const slot = k & this.mask;
    const work = this.endWork;
    this.blocks[slot * BLOCK_STRIDE + LENGTH] = length;
    this.blocks[slot * BLOCK_STRIDE + ACCEL] = accel;
    this.blocks[slot * BLOCK_STRIDE + MAX_ENTRY2] = maxEntry2;
    this.blocks[slot * BLOCK_STRIDE + WORK] = work;
    this.blocks[slot * BLOCK_STRIDE + EXIT2] = 0;
    if (k === this.first) {
      // The new block is the front: its entry is fixed, so junction k needs no candidate.
      this.blocks[slot * BLOCK_STRIDE + ENTRY2] = this.frontEntry2;
    } else {
      // Junction k was the end of the path, at rest; it is now interior, with its real cap.
      this.blocks[slot * BLOCK_STRIDE + ENTRY2] = 0;
      this.pushCandidate(k, maxEntry2 + 2 * work);
    }
    this.endWork = work + accel * length;
    this.end = k + 1;
    this.advance(false);
  }

  /** Appends a block given as an object with the planner's inputs. */
  appendBlock(block: BlockLimits): void {
    this.append(block.length, block.accel, block.maxEntry2);
  }

  /**
   * Finalises every block as if the path ended here, at rest. For a path known to
   * be complete (planPath), and before locking the last blocks of a finished job.
   */
  planToRest(): void {
    this.advance(true);
  }

  /**
   * Locks the front block for transmission and returns its exit speed², final from
   * now on and the entry speed² of the next block. Blocks that become final as a
   * result are reported with offsets from the new front.
   */
  lockFront(): number {
    if (this.size === 0) throw new Error('lockFront: no unlocked block');
    const slot = this.first & this.mask;
    const decidedNow = this.plannedCount === 0;
    if (decidedNow) {
      // Not final yet: decide with what is known now (always stoppable: e ≤ b).
      const exit2 = this.frontExit2();
      this.blocks[slot * BLOCK_STRIDE + EXIT2] = exit2;
      if (this.size > 1) this.blocks[((this.first + 1) & this.mask) * BLOCK_STRIDE + ENTRY2] = exit2;
    } else {
      this.plannedCount--;
    }
    const exit2 = this.blocks[slot * BLOCK_STRIDE + EXIT2];
    this.frontEntry2 = exit2;
    this.first++;
    // The candidate at the new front junction is not needed any more (the front's entry is fixed).
    while (this.candHead < this.candTail && this.cands[(this.candHead & this.mask) * 2] <= this.first) this.candHead++;
    if (this.size === 0) this.reset();
    // Every operation leaves the planned pointer as far as it can go. Locking a front
    // that was already final changes neither the entry there nor any bound (W and C
    // are absolute), so the pointer stays; only an exit decided now, which fixes the
    // next block's entry, may let it move.
    else if (decidedNow) this.advance(false);
    return exit2;
  }

  /** The exit speed² that lockFront() would give the front block now. */
  frontExit2(): number {
    const slot = this.first & this.mask;
    if (this.plannedCount > 0) return this.blocks[slot * BLOCK_STRIDE + EXIT2];
    if (this.size === 1) return 0;
    const reach2 = this.blocks[slot * BLOCK_STRIDE + ENTRY2] + 2 * this.blocks[slot * BLOCK_STRIDE + ACCEL] * this.blocks[slot * BLOCK_STRIDE + LENGTH];
    return this.exitWithin(this.first, Math.min(this.backwardBound(this.first + 1, false), reach2));
  }

  /**
   * Removes every unlocked block from the i-th on (0 = the front) and returns how
   * many went. The remaining plan is recomputed from the front, and its final
   * blocks are reported again.
   */
  truncate(i: number): number {
    const keep = Math.max(0, Math.min(i, this.size));
    const removed = this.size - keep;
    this.end = this.first + keep;
    this.rebuild();
    return removed;
  }

  /**
   * Removes every unlocked block and forgets the last locked exit: the next block
   * appended starts from rest (a job resumed after the machine stopped off its plan).
   */
  clearToRest(): number {
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
    const slot = this.first & this.mask;
    if (e > this.blocks[slot * BLOCK_STRIDE + MAX_ENTRY2] + slack) return false;
    const after = count === 1 ? 0 : this.backwardBound(this.first + 1, false);
    return e <= after + 2 * this.blocks[slot * BLOCK_STRIDE + ACCEL] * this.blocks[slot * BLOCK_STRIDE + LENGTH] + slack;
  }

  /**
   * Computes the speeds of the blocks beyond the planned pointer as the plan stands
   * (ending at rest) and reports each to `write`. These values are provisional:
   * more blocks may raise them. For display only; it changes nothing that is final.
   * O(unplanned blocks).
   */
  fillProvisional(write: ProvisionalListener): void {
    const start = this.first + this.plannedCount;
    const end = this.end;
    if (start >= end) return;
    const m = this.mask;
    // Backward pass from the end at rest: b at each block's exit, kept in exit2s (working values:
    // advance() writes an unplanned block's exit2 before it reads it).
    let next2 = 0;
    for (let k = end - 1; k > start; k--) {
      const s = k & m;
      this.blocks[s * BLOCK_STRIDE + EXIT2] = next2;
      next2 = Math.min(this.blocks[s * BLOCK_STRIDE + MAX_ENTRY2], next2 + 2 * this.blocks[s * BLOCK_STRIDE + ACCEL] * this.blocks[s * BLOCK_STRIDE + LENGTH]);
    }
    this.blocks[(start & m) * BLOCK_STRIDE + EXIT2] = next2;
    // Forward pass from the pointer's final entry.
    let entry2 = this.blocks[(start & m) * BLOCK_STRIDE + ENTRY2];
    for (let k = start; k < end; k++) {
      const s = k & m;
      const exit2 = Math.min(this.blocks[s * BLOCK_STRIDE + EXIT2], entry2 + 2 * this.blocks[s * BLOCK_STRIDE + ACCEL] * this.blocks[s * BLOCK_STRIDE + LENGTH]);
      write(k - this.first, entry2, exit2);
      entry2 = exit2;
    }
    // Only unplanned blocks' entry2/exit2 were touched here, which advance() writes before it reads.
  }

  // --- internals ---

  private pushCandidate(junction: number, value: number): void {
    const m = this.mask;
    while (this.candTail > this.candHead && this.cands[((this.candTail - 1) & m) * 2 + 1] > value) this.candTail--;
    const slot = this.candTail & m;
    this.cands[slot * 2] = junction;
    this.cands[slot * 2 + 1] = value;
    this.candTail++;
  }

  private workAt(junction: number): number {
    return junction < this.end ? this.blocks[(junction & this.mask) * BLOCK_STRIDE + WORK] : this.endWork;
  }

  /**
   * b at a junction: min(later interior candidates' C, the end's 2·W_end) − 2·W.
   * `consume` drops the candidates before it, which the forward pass (monotone)
   * never needs again. Leaves in boundSetByEnd whether the end-of-path rest sets
   * the minimum (then more blocks may raise it).
   */
  private backwardBound(junction: number, consume = true): number {
    const m = this.mask;
    let h = this.candHead;
    const t = this.candTail;
    while (h < t && this.cands[(h & m) * 2] < junction) h++;
    if (consume) this.candHead = h;
    const interior = h < t ? this.cands[(h & m) * 2 + 1] : Infinity;
    const end = 2 * this.endWork;
    this.boundSetByEnd = end < interior;
    return Math.min(interior, end) - 2 * this.workAt(junction);
  }

  /**
   * Block k's exit speed² `exit2` = min(f_k + 2·a_k·L_k, b_{k+1}), held to junction k + 1's
   * own cap. In exact arithmetic that changes nothing: b_{k+1} is a minimum over j ≥ k + 1
   * whose j = k + 1 term is cap_{k+1} itself, so b_{k+1} ≤ cap_{k+1}. But b is computed as
   * C_j − 2·W_{k+1} with C_j = cap_j + 2·W_j, a difference of two sums of the work prefix W,
   * which grows along the path: each rounding is up to half an ulp of 2·W, about 2.2e-16·W
   * mm²/s², whatever the cap. Where the cap is far smaller than that (a sub-µm segment whose
   * cruise cap a link's duration floor made tiny: v² ≈ 3e-14 after W ≈ 8e-6) the rounding
   * put the junction speed² 4e-8 (relative) above the cap, the segment cruised above its
   * floor speed and lasted less than the floor. Taking the cap itself where it binds makes
   * the exit exact there: e ≤ cap holds to the bit.
   */
  private exitWithin(k: number, exit2: number): number {
    return Math.min(exit2, this.blocks[((k + 1) & this.mask) * BLOCK_STRIDE + MAX_ENTRY2]);
  }

  /** Moves the planned pointer forward as far as the plan is final. */
  private advance(toRest: boolean): void {
    const end = this.end;
    const m = this.mask;
    let p = this.first + this.plannedCount;
    while (p < end) {
      const s = p & m;
      const reach2 = this.blocks[s * BLOCK_STRIDE + ENTRY2] + 2 * this.blocks[s * BLOCK_STRIDE + ACCEL] * this.blocks[s * BLOCK_STRIDE + LENGTH];
      let exit2: number;
      if (p + 1 === end) {
        if (!toRest) break;
        exit2 = 0;
      } else {
        const bound = this.backwardBound(p + 1);
        if (this.boundSetByEnd && reach2 > bound && !toRest) break;
        exit2 = this.exitWithin(p, Math.min(bound, reach2));
        this.blocks[((p + 1) & m) * BLOCK_STRIDE + ENTRY2] = exit2;
      }
      this.blocks[s * BLOCK_STRIDE + EXIT2] = exit2;
      this.plannedCount++;
      this.onFinal?.(p - this.first);
      p++;
    }
  }

  /** Forgets the blocks' bookkeeping (not their inputs); the front stays where it is. */
  private reset(): void {
    this.candHead = 0;
    this.candTail = 0;
    this.plannedCount = 0;
    this.endWork = 0;
  }

  /** Recomputes the work prefix, the candidates and the forward pass from the front, from the inputs kept in the ring. */
  private rebuild(): void {
    const from = this.first;
    const to = this.end;
    this.reset();
    this.end = from;
    const m = this.mask;
    for (let k = from; k < to; k++) {
      const s = k & m;
      this.append(this.blocks[s * BLOCK_STRIDE + LENGTH], this.blocks[s * BLOCK_STRIDE + ACCEL], this.blocks[s * BLOCK_STRIDE + MAX_ENTRY2]);
    }
  }

  /** Doubles the rings. */
  private grow(): void {
    this.resize(2 * (this.mask + 1));
  }

  /** Makes the rings `capacity` slots (a power of two), keeping every block and candidate at its slot for the new mask. */
  private resize(capacity: number): void {
    const oldMask = this.mask;
    const mask = capacity - 1;
    const move = (from: Float64Array<ArrayBuffer>, stride: number, first: number, end: number): Float64Array<ArrayBuffer> => {
      const grown = new Float64Array(capacity * stride);
      for (let k = first; k < end; k++) {
        const o = (k & oldMask) * stride;
        grown.set(from.subarray(o, o + stride), (k & mask) * stride);
      }
      return grown;
    };
    this.blocks = move(this.blocks, BLOCK_STRIDE, this.first, this.end);
    this.cands = move(this.cands, 2, this.candHead, this.candTail);
    this.mask = mask;
  }
}
