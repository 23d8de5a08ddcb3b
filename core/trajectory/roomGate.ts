/**
 * The queue's door for producers (queue.ts): the slots promised to producers that
 * waited for room, and the producers still waiting, served in the order they came.
 *
 * The queue decides whether it has room (TrajectoryQueue.hasRoom, which counts the
 * slots promised here as taken); the gate only keeps the line. A producer that finds
 * room and nobody ahead of it takes a slot at once; one that does not waits until
 * the queue admits it (admitNext, oldest first), and gives the slot back with
 * release() if it abandons its move. An aborted waiter leaves the line at once, so it
 * never takes a slot.
 */
import { abortedError } from '../errors.ts';

const WAIT = 'the wait for room in the queue';

export class RoomGate {
  /** Slots promised to producers that have not appended their move yet. */
  reserved = 0;
  private waiters: Array<() => void> = [];

  /** Producers waiting for room. */
  get waiting(): number {
    return this.waiters.length;
  }

  /**
   * Resolves when a slot is promised to the caller: at once if `roomNow` (the queue
   * has room) and nobody waits, else when admitNext() reaches it. Rejects with
   * ABORTED if `signal` aborts first, having taken nothing.
   */
  reserve(roomNow: boolean, signal?: AbortSignal): Promise<void> {
    if (signal?.aborted) return Promise.reject(abortedError(signal, WAIT));
    if (roomNow && this.waiters.length === 0) {
      this.reserved++;
      return Promise.resolve();
    }
    if (!signal) return new Promise((resolve) => this.waiters.push(resolve));
    return new Promise((resolve, reject) => {
      const waiter = () => {
        signal.removeEventListener('abort', onAbort);
        resolve();
      };
      const onAbort = () => {
        this.waiters = this.waiters.filter((w) => w !== waiter);
        reject(abortedError(signal, WAIT));
      };
      signal.addEventListener('abort', onAbort, { once: true });
      this.waiters.push(waiter);
    });
  }

  /** A promised slot is used (its move appended) or given back (its move abandoned). */
  release(): void {
    this.reserved--;
  }

  /** Promises a slot to the producer that has waited longest and wakes it; the queue calls it while it has room. */
  admitNext(): void {
    const resolve = this.waiters.shift() as () => void;
    this.reserved++;
    resolve();
  }
}
