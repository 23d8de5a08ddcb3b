/**
 * Arrays used as queues (the planner's blocks, the trajectory queue's live
 * segments) consume items from the front by moving a head index, and now and then
 * slice the spent prefix away. Slicing once the spent items outnumber the rest
 * costs O(1) amortised per item.
 *
 * The spent prefix is kept short, too: an item still referenced from it, though
 * the queue is done with it, survives every young-generation collection, which
 * copies it. A segment with its arrays is about 1 kB, so a prefix of a thousand
 * dead segments doubled the work of each collection.
 */
const MIN_SPENT = 64;

/** Whether an array-backed queue whose first `spent` of `length` items are consumed should drop them now. */
export function shouldDropSpent(spent: number, length: number): boolean {
  return spent > MIN_SPENT && spent * 2 > length;
}
