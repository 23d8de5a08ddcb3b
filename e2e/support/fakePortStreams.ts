/**
 * A fake port's two streams, at the end that opens it (the MAXL worker, or the
 * page for the bridge), over a MessageChannel to its board in the fake boards'
 * worker (fakeBoardLink.ts).
 *
 * Every chunk written carries the time it was written, `sentAt_ms` (epoch ms:
 * `performance.timeOrigin + performance.now()`, comparable between a page and
 * its workers). The board delivers it at that time on its own clock, whenever
 * its worker gets the CPU to read it, as a real board's USB hardware receives
 * the bytes when the host sends them, whatever its own program is doing. So the
 * fake boards, which share the browser's CPU, do not make the author look late;
 * the author's own lateness (the time it wrote) still reaches them whole.
 */

/** A chunk on its way to a board. */
export interface StampedChunk {
  bytes: Uint8Array;
  /** When the opener's port was written: epoch ms. */
  sentAt_ms: number;
}

/** The board's end says it closed. */
export interface ChannelClosed {
  closed: true;
}

/** The opener's readable and writable for a board behind `channel`. */
export function streamsOverChannel(channel: MessagePort): { readable: ReadableStream<Uint8Array>; writable: WritableStream<Uint8Array> } {
  let open = true;
  const readable = new ReadableStream<Uint8Array>({
    start: (controller) => {
      channel.onmessage = (m: MessageEvent<Uint8Array | ChannelClosed>) => {
        if (!open) return;
        if (m.data instanceof Uint8Array) controller.enqueue(m.data);
        else {
          open = false;
          controller.close();
        }
      };
    },
    cancel: () => {
      open = false;
    },
  });
  const writable = new WritableStream<Uint8Array>({
    write: (chunk) => {
      const bytes = chunk.slice();
      const message: StampedChunk = { bytes, sentAt_ms: performance.timeOrigin + performance.now() };
      channel.postMessage(message, [bytes.buffer]);
    },
  });
  return { readable, writable };
}
