/**
 * Lets the worker's event loop run (incoming commands, timers) in the middle of
 * a long loop. A MessageChannel round trip is not clamped the way nested
 * setTimeout(0) is.
 */
const channel = new MessageChannel();
const waiting: Array<() => void> = [];
channel.port1.onmessage = () => waiting.shift()?.();

export function yieldToEvents(): Promise<void> {
  return new Promise((resolve) => {
    waiting.push(resolve);
    channel.port2.postMessage(0);
  });
}
