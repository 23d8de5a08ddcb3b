/**
 * Frames (docs/protocol.md §3): packet = seq, type, payload, CRC-16; frame =
 * COBS(packet) then 0x00. FrameReceiver turns a byte stream back into packets,
 * reporting each frame it has to drop and why.
 */
import { cobsDecode, cobsEncode } from './cobs.ts';
import { crc16 } from './crc16.ts';
import { decodePayload, encodePayload, WireError, type DecodeContext, type Message } from './messages.ts';
import { MAX_ENCODED, MAX_PACKET, MessageType } from './protocol.ts';

export interface Packet {
  seq: number;
  message: Message;
}

/** A frame's packet before its payload is decoded into a message. */
export interface RawPacket {
  seq: number;
  typeCode: number;
  payload: Uint8Array;
}

export function encodeFrame(seq: number, message: Message): Uint8Array {
  const payload = encodePayload(message);
  const packet = new Uint8Array(payload.length + 4);
  if (packet.length > MAX_PACKET) throw new WireError('TOO_LONG', `${message.type} payload of ${payload.length} bytes exceeds ${MAX_PACKET - 4}`);
  packet[0] = seq & 0xff;
  packet[1] = MessageType[message.type];
  packet.set(payload, 2);
  const crc = crc16(packet, 0, packet.length - 2);
  packet[packet.length - 2] = crc & 0xff;
  packet[packet.length - 1] = crc >> 8;
  const encoded = cobsEncode(packet);
  const frame = new Uint8Array(encoded.length + 1);
  frame.set(encoded);
  return frame; // last byte 0x00: the delimiter
}

/** Checks one COBS-encoded frame (without its delimiter) and splits its packet. */
export function unpackFrame(encoded: Uint8Array): RawPacket {
  if (encoded.length > MAX_ENCODED) throw new WireError('TOO_LONG', `frame of ${encoded.length} bytes exceeds ${MAX_ENCODED}`);
  const packet = cobsDecode(encoded);
  if (packet === null) throw new WireError('BAD_COBS', 'a COBS code byte points past the end of the frame');
  if (packet.length < 4) throw new WireError('TOO_SHORT', `packet of ${packet.length} bytes is shorter than 4`);
  const crc = packet[packet.length - 2] | (packet[packet.length - 1] << 8);
  if (crc !== crc16(packet, 0, packet.length - 2)) throw new WireError('BAD_CRC', 'CRC mismatch');
  return { seq: packet[0], typeCode: packet[1], payload: packet.subarray(2, packet.length - 2) };
}

/** Decodes one whole frame, with or without its trailing 0x00. */
export function decodeFrame(frame: Uint8Array, ctx: DecodeContext): Packet {
  const body = frame.length > 0 && frame[frame.length - 1] === 0 ? frame.subarray(0, frame.length - 1) : frame;
  const raw = unpackFrame(body);
  return { seq: raw.seq, message: decodePayload(raw.typeCode, raw.payload, ctx, raw.seq) };
}

/**
 * Splits a byte stream into frames. Bytes beyond MAX_ENCODED before a delimiter
 * are dropped (TOO_LONG, reported once at the delimiter); empty frames are
 * ignored.
 */
export class FrameReceiver {
  private buf = new Uint8Array(MAX_ENCODED);
  private length = 0;
  private overflow = false;

  constructor(
    /** Each good packet, and the bytes its frame took on the wire (COBS and the delimiter included). */
    private readonly onPacket: (packet: RawPacket, frameBytes: number) => void,
    private readonly onError: (error: WireError) => void,
  ) {}

  push(bytes: Uint8Array): void {
    for (let i = 0; i < bytes.length; i++) {
      const b = bytes[i];
      if (b !== 0) {
        if (this.length < MAX_ENCODED) this.buf[this.length++] = b;
        else this.overflow = true;
        continue;
      }
      const n = this.length;
      const overflow = this.overflow;
      this.length = 0;
      this.overflow = false;
      if (overflow) {
        this.onError(new WireError('TOO_LONG', `frame longer than ${MAX_ENCODED} bytes`));
        continue;
      }
      if (n === 0) continue;
      let packet: RawPacket;
      try {
        packet = unpackFrame(this.buf.slice(0, n));
      } catch (err) {
        if (err instanceof WireError) {
          this.onError(err);
          continue;
        }
        throw err;
      }
      this.onPacket(packet, n + 1);
    }
  }
}
