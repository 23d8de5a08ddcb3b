/**
 * A fake port's two streams, at the end that opens it (the MAXL worker, or the
 * page for the bridge), over a WebSocket to its board in the fake boards' Node
 * process (fakeBoardsProcess.ts, fakeBoardLink.ts).
 *
 * Every chunk written carries the time it was written, `sentAt_ms` (epoch ms:
 * `performance.timeOrigin + performance.now()`, comparable between a page, its
 * workers and a Node process on the same machine: all count from the system's
 * clock). The board delivers it at that time on its own clock, whenever its
 * process gets the CPU to read it, as a real board's USB hardware receives the
 * bytes when the host sends them, whatever its own program is doing. So a fake
 * board held back does not make the author look late; the author's own lateness
 * (the time it wrote) still reaches it whole.
 *
 * The wire: the opener sends one binary message per chunk, 8 bytes of
 * `sentAt_ms` (float64, little-endian) then the bytes; the board sends its bytes
 * as they are, one binary message per chunk, and closes the socket when its
 * link closes.
 */

/** A chunk on its way to a board. */
export interface StampedChunk {
  bytes: Uint8Array;
  /** When the opener's port was written: epoch ms. */
  sentAt_ms: number;
}

const STAMP_BYTES = 8;

/** A chunk as it goes on the wire: its stamp, then its bytes. */
export function encodeStampedChunk({ bytes, sentAt_ms }: StampedChunk): Uint8Array<ArrayBuffer> {
  const frame = new Uint8Array(STAMP_BYTES + bytes.length);
  new DataView(frame.buffer).setFloat64(0, sentAt_ms, true);
  frame.set(bytes, STAMP_BYTES);
  return frame;
}

/** The other way; a frame too short to hold a stamp is a broken opener, said so. */
export function decodeStampedChunk(frame: Uint8Array): StampedChunk {
  if (frame.length < STAMP_BYTES) throw new Error(`a fake port's chunk is ${frame.length} bytes, shorter than its ${STAMP_BYTES}-byte time stamp`);
  const sentAt_ms = new DataView(frame.buffer, frame.byteOffset, frame.byteLength).getFloat64(0, true);
  return { bytes: frame.slice(STAMP_BYTES), sentAt_ms };
}

/** The opener's readable and writable for the board behind the WebSocket at `url` (resolves once it is connected). */
export async function streamsOverSocket(url: string): Promise<{ readable: ReadableStream<Uint8Array>; writable: WritableStream<Uint8Array>; close(): void }> {
  const socket = new WebSocket(url);
  socket.binaryType = 'arraybuffer';
  await new Promise<void>((resolve, reject) => {
    socket.onopen = () => resolve();
    socket.onerror = () => reject(new DOMException(`the fake board at ${url} could not be reached`, 'NetworkError'));
  });
  let open = true;
  const readable = new ReadableStream<Uint8Array>({
    start: (controller) => {
      socket.onmessage = (m: MessageEvent<ArrayBuffer>) => {
        if (open) controller.enqueue(new Uint8Array(m.data));
      };
      socket.onclose = () => {
        if (!open) return;
        open = false;
        controller.close();
      };
    },
    cancel: () => {
      open = false;
    },
  });
  const writable = new WritableStream<Uint8Array>({
    write: (chunk) => {
      if (socket.readyState !== WebSocket.OPEN) throw new DOMException('The device has been lost.', 'NetworkError');
      socket.send(encodeStampedChunk({ bytes: chunk, sentAt_ms: performance.timeOrigin + performance.now() }));
    },
  });
  return { readable, writable, close: () => socket.close() };
}
