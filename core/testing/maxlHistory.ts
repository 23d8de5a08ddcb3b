/**
 * For tests that compare two ways of producing the same plan: an author on a
 * config (with a queue listener or without: the queue keeps objects or columns),
 * and everything its history recorded, in order.
 */
import { createMAXL, type Maxl } from '../maxl.ts';
import type { MaxlConfig } from '../config/types.ts';

export function machine(config: MaxlConfig, listening: boolean): Maxl {
  const maxl = createMAXL(config, { initialPosition: [0, 0] });
  if (listening) maxl.queue.subscribe(() => {});
  return maxl;
}

export function historyOf(maxl: Maxl): Array<ReturnType<Maxl['history']['at']>> {
  const out: Array<ReturnType<Maxl['history']['at']>> = [];
  for (let i = 0; i < maxl.history.size; i++) out.push(maxl.history.at(i));
  return out;
}
