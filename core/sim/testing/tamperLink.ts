/**
 * A link whose frames to the device of one message type pass through `tamper` on
 * the way: it gets each one's sequence number and decoded message and returns the
 * message to send instead (or the same one). Other frames pass unchanged. The changed frame is encoded afresh, with a
 * correct CRC, so the device reads it and judges its content: a way to make a
 * real device refuse a frame for what it says, not for how it arrived.
 */
import { encodeFrame, unpackFrame } from '../../net/frame.ts';
import type { Link } from '../../net/link.ts';
import { decodePayload, type Message } from '../../net/messages.ts';
import { MessageType } from '../../net/protocol.ts';

export type Tamper = (seq: number, message: Message) => Message;

export function tamperLink(link: Link, type: Message['type'], tamper: Tamper): Link {
  const writer = link.writable.getWriter();
  let pending: number[] = [];
  const writable = new WritableStream<Uint8Array>({
    write: async (chunk) => {
      const out: number[] = [];
      for (const byte of chunk) {
        if (byte !== 0) {
          pending.push(byte);
          continue;
        }
        const frame = Uint8Array.from(pending);
        pending = [];
        const raw = unpackFrame(frame);
        if (raw.typeCode !== MessageType[type]) {
          out.push(...frame, 0);
          continue;
        }
        const message = decodePayload(raw.typeCode, raw.payload, { positionSlots: 0, channels: 0 }, raw.seq);
        out.push(...encodeFrame(raw.seq, tamper(raw.seq, message)));
      }
      if (out.length > 0) await writer.write(Uint8Array.from(out));
    },
    close: () => writer.close(),
  });
  return { readable: link.readable, writable, label: link.label, close: link.close?.bind(link), bytesPerSecond: link.bytesPerSecond, uartByteTime_us: link.uartByteTime_us };
}
