/**
 * How late the streamer's own pumps have come lately: the author's thread held
 * back (a busy machine, a long task in the same thread). A pump is scheduled for a
 * time; it runs `late` µs after it. The streamer keeps `lead` of motion sent ahead,
 * so a pump late by more than the lead lets the devices run out. The round trip
 * (which sets the lead) sees such delays only when a reply happens to wait behind
 * them, so the lead also takes the worst lateness of the last `window_us` of pumps
 * (Streamer, lagAllowance_us): on a quiet machine it is the timer's own jitter, and
 * the margin already holds that; on a loaded one the lead grows to cover the
 * hold-backs the machine has just shown, and shrinks again `window_us` after them.
 *
 * Under virtual time a pump is never late, so nothing changes there.
 *
 * The worst over a sliding window in O(1) amortised per note: a deque of (time,
 * lateness) whose latenesses decrease from front to back. A new note drops every
 * entry at the back that is not later than it (they can never be the maximum
 * again while it is in the window), and entries older than the window leave the
 * front; the front is the maximum.
 */
export class PumpLag {
  private readonly at: number[] = [];
  private readonly late: number[] = [];
  private head = 0;

  constructor(private readonly window_us: number) {}

  /** A pump scheduled for `due_us` ran at `now_us`. */
  note(due_us: number, now_us: number): void {
    const late = Math.max(0, now_us - due_us);
    while (this.late.length > this.head && this.late[this.late.length - 1] <= late) {
      this.at.pop();
      this.late.pop();
    }
    this.at.push(now_us);
    this.late.push(late);
    this.expire(now_us);
  }

  /** The worst lateness (µs) of the pumps in the window ending at `now_us`; 0 with none. */
  worst_us(now_us: number): number {
    this.expire(now_us);
    return this.late.length > this.head ? this.late[this.head] : 0;
  }

  private expire(now_us: number): void {
    while (this.late.length > this.head && this.at[this.head] < now_us - this.window_us) this.head++;
    // Compact now and then, so the arrays do not grow without bound.
    if (this.head > 64 && this.head * 2 > this.late.length) {
      this.at.splice(0, this.head);
      this.late.splice(0, this.head);
      this.head = 0;
    }
  }
}
