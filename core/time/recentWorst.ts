/**
 * The worst of values noted over a sliding window of time: how late a thread's
 * timers came lately (RealScheduler), how late the streamer's pumps came, the
 * worst round trip the links showed (core/net/streamer.ts).
 *
 * Why the streamer needs it: it keeps `lead` of motion sent ahead, so a pump late
 * by more than the lead, or bytes held up on their way for longer, let the devices
 * run out. The round trip measured now sees such delays only when a reply happens
 * to wait behind them; a machine that has just held the author back will likely
 * do so again. So the lead takes the worst of the last window: on a quiet machine
 * that is the timers' own jitter, which the margins already hold; on a loaded one
 * the lead grows to cover the hold-backs the machine has just shown, and shrinks
 * again a window after them. Under virtual time nothing is ever late.
 *
 * O(1) amortised per note: a deque of (time, value) whose values decrease from
 * front to back. A new note drops every entry at the back that is not larger
 * (they can never be the maximum again while it is in the window), and entries
 * older than the window leave the front; the front is the maximum.
 *
 * The worst since a later time S (`worst(now, S)`) is exact too: it is the first
 * entry at or after S. Let M be the largest note made at or after S (the latest of
 * equals). Only a later note at least as large removes a note from the back, and
 * none is larger than M, so M or an equal note after it is still in the deque; the
 * first entry at or after S is a note made at or after S, so it is at most M, and
 * it comes no later than M's entry in a deque of decreasing values, so it is at
 * least M.
 */
export class RecentWorst {
  private readonly at: number[] = [];
  private readonly value: number[] = [];
  private head = 0;

  constructor(private readonly window_us: number) {}

  /** A value seen at `at_us` (times never go back). */
  note(at_us: number, value: number): void {
    while (this.value.length > this.head && this.value[this.value.length - 1] <= value) {
      this.at.pop();
      this.value.pop();
    }
    this.at.push(at_us);
    this.value.push(value);
    this.expire(at_us);
  }

  /** A timer due at `due_us` ran at `now_us`: notes how late it came (0 if early). */
  noteLateness(due_us: number, now_us: number): void {
    this.note(now_us, Math.max(0, now_us - due_us));
  }

  /** The worst value noted in the window ending at `now_us`, and not before `since_us`; 0 with none. */
  worst(now_us: number, since_us = -Infinity): number {
    this.expire(now_us);
    let i = this.head;
    while (i < this.at.length && this.at[i] < since_us) i++;
    return i < this.value.length ? this.value[i] : 0;
  }

  private expire(now_us: number): void {
    while (this.value.length > this.head && this.at[this.head] < now_us - this.window_us) this.head++;
    // Compact now and then, so the arrays do not grow without bound.
    if (this.head > 64 && this.head * 2 > this.value.length) {
      this.at.splice(0, this.head);
      this.value.splice(0, this.head);
      this.head = 0;
    }
  }
}
