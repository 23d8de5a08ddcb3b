/**
 * Fuzzing the TypeScript decoder (frame.ts, messages.ts, cobs.ts, bytes.ts): random
 * bytes, well-framed random payloads of every type, and mutated valid frames (the
 * shared vectors with bytes flipped, inserted, dropped or cut). Whatever comes in,
 * a rejection is a WireError with one of its codes, never a RangeError, TypeError or
 * anything else; and what is accepted is what the encoder would write: encoding the
 * decoded message succeeds and decodes to the same message again (the decoder
 * accepts nothing the encoder refuses, such as a control byte in a name).
 */
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { cobsEncode } from './cobs.ts';
import { crc16 } from './crc16.ts';
import { decodeFrame, FrameReceiver, type RawPacket } from './frame.ts';
import { decodePayload, encodePayload, WireError, type DecodeContext, type Message, type WireErrorCode } from './messages.ts';
import { MAX_PAYLOAD, MessageType } from './protocol.ts';

const CODES: readonly WireErrorCode[] = ['TOO_LONG', 'BAD_COBS', 'TOO_SHORT', 'BAD_CRC', 'MALFORMED', 'UNKNOWN_MESSAGE'];
const VECTORS = JSON.parse(readFileSync(fileURLToPath(new URL('../../docs/protocol-vectors.json', import.meta.url)), 'utf8')) as {
  vectors: Array<{ frame: string; context: DecodeContext; error?: string }>;
};
const validFrames = VECTORS.vectors.filter((v) => !v.error).map((v) => ({ frame: Uint8Array.from(Buffer.from(v.frame, 'hex')), context: v.context }));

/** The decoding contexts a session can have: up to 8 position slots, up to 12 sensor channels. */
const context = fc.record({ positionSlots: fc.integer({ min: 0, max: 8 }), channels: fc.integer({ min: 0, max: 12 }) });
const knownType = fc.constantFrom(...Object.values(MessageType));
const anyType = fc.oneof(knownType, fc.integer({ min: 0, max: 255 }));

/** A packet with a correct CRC around the given type and payload, COBS-encoded and delimited. */
function frameAround(seq: number, typeCode: number, payload: Uint8Array): Uint8Array {
  const packet = new Uint8Array(payload.length + 4);
  packet[0] = seq;
  packet[1] = typeCode;
  packet.set(payload, 2);
  const crc = crc16(packet, 0, packet.length - 2);
  packet[packet.length - 2] = crc & 0xff;
  packet[packet.length - 1] = crc >> 8;
  return Uint8Array.from([...cobsEncode(packet), 0]);
}

/** Runs `decode`; fails the property on anything thrown that is not a WireError with a known code. */
function typedOutcome<T>(decode: () => T): { ok: true; value: T } | { ok: false; error: WireError } {
  try {
    return { ok: true, value: decode() };
  } catch (err) {
    if (!(err instanceof WireError)) throw new Error(`untyped rejection: ${String(err)} (${(err as Error)?.constructor?.name})`);
    expect(CODES).toContain(err.code);
    return { ok: false, error: err };
  }
}

/** What is accepted must be what the encoder writes: it re-encodes, and decodes back the same. */
function expectEncoderAgrees(typeCode: number, message: Message, ctx: DecodeContext): void {
  let again: Uint8Array;
  try {
    again = encodePayload(message);
  } catch (err) {
    throw new Error(`the decoder accepted a ${message.type} the encoder refuses: ${String(err)}`);
  }
  expect(decodePayload(typeCode, again, ctx)).toEqual(message);
}

type Mutation = { kind: 'flip' | 'insert' | 'delete' | 'set'; at: number; byte: number };
const mutation: fc.Arbitrary<Mutation> = fc.record({
  kind: fc.constantFrom('flip', 'insert', 'delete', 'set'),
  at: fc.nat(),
  byte: fc.integer({ min: 0, max: 255 }),
});
function mutate(frame: Uint8Array, mutations: Mutation[], cut: number | null): Uint8Array {
  const bytes = [...frame];
  for (const m of mutations) {
    const at = bytes.length === 0 ? 0 : m.at % bytes.length;
    if (m.kind === 'flip') bytes[at] ^= 1 << (m.byte & 7);
    else if (m.kind === 'insert') bytes.splice(at, 0, m.byte);
    else if (m.kind === 'delete') bytes.splice(at, 1);
    else bytes[at] = m.byte;
  }
  return Uint8Array.from(cut === null ? bytes : bytes.slice(0, cut % (bytes.length + 1)));
}

describe('the TS decoder under fuzzing: every rejection is typed', () => {
  it('random bytes as a frame', () => {
    fc.assert(
      fc.property(fc.uint8Array({ maxLength: 200 }), context, (bytes, ctx) => {
        typedOutcome(() => decodeFrame(bytes, ctx));
      }),
    );
  });

  it('random payloads of every type in well-formed frames: MALFORMED or UNKNOWN_MESSAGE, or a message the encoder writes back', () => {
    fc.assert(
      fc.property(fc.integer({ min: 0, max: 255 }), anyType, fc.uint8Array({ maxLength: MAX_PAYLOAD }), context, (seq, typeCode, payload, ctx) => {
        const r = typedOutcome(() => decodeFrame(frameAround(seq, typeCode, payload), ctx));
        if (!r.ok) {
          expect(['MALFORMED', 'UNKNOWN_MESSAGE']).toContain(r.error.code);
          expect(r.error.seq).toBe(seq);
          expect(r.error.typeCode).toBe(typeCode);
          return;
        }
        expect(r.value.seq).toBe(seq);
        expectEncoderAgrees(typeCode, r.value.message, ctx);
      }),
    );
  });

  it('names: a control or non-ASCII byte is MALFORMED, as the encoder refuses it', () => {
    fc.assert(
      fc.property(
        fc.string({ unit: fc.integer({ min: 0x20, max: 0x7e }).map((c) => String.fromCharCode(c)), maxLength: 30 }),
        fc.oneof(fc.integer({ min: 0, max: 0x1f }), fc.integer({ min: 0x7f, max: 0xff })),
        fc.nat(),
        (name, bad, where) => {
          const at = where % (name.length + 1);
          const bytes = [...name].map((c) => c.charCodeAt(0));
          bytes.splice(at, 0, bad);
          const payload = Uint8Array.from([3, 0, 2, bytes.length, ...bytes]); // READER: index, kind, channels, name
          const r = typedOutcome(() => decodePayload(MessageType.READER, payload, { positionSlots: 1, channels: 0 }));
          expect(r.ok).toBe(false);
          if (!r.ok) expect(r.error.code).toBe('MALFORMED');
          expect(() => encodePayload({ type: 'READER', index: 3, kind: 0, channels: 2, name: String.fromCharCode(...bytes) })).toThrow();
        },
      ),
    );
  });

  it('mutated valid frames (the shared vectors): typed errors, or a message the encoder writes back', () => {
    fc.assert(
      fc.property(
        fc.constantFrom(...validFrames),
        fc.array(mutation, { minLength: 1, maxLength: 6 }),
        fc.option(fc.nat(), { nil: null }),
        ({ frame, context: ctx }, mutations, cut) => {
          const bytes = mutate(frame, mutations, cut);
          const r = typedOutcome(() => decodeFrame(bytes, ctx));
          if (r.ok) expectEncoderAgrees(MessageType[r.value.message.type], r.value.message, ctx);
        },
      ),
    );
  });

  it('a stream of mutated and random frames through the FrameReceiver, in random chunks: it never throws, and reports only WireErrors', () => {
    fc.assert(
      fc.property(
        fc.array(
          fc.oneof(
            fc.tuple(fc.constantFrom(...validFrames), fc.array(mutation, { maxLength: 4 })).map(([v, m]) => mutate(v.frame, m, null)),
            fc.uint8Array({ maxLength: 120 }),
          ),
          { maxLength: 20 },
        ),
        fc.array(fc.integer({ min: 1, max: 50 }), { minLength: 1, maxLength: 20 }),
        context,
        (pieces, cuts, ctx) => {
          const stream = Uint8Array.from(pieces.flatMap((p) => [...p]));
          const packets: RawPacket[] = [];
          const errors: unknown[] = [];
          const rx = new FrameReceiver(
            (p) => packets.push(p),
            (e) => errors.push(e),
          );
          for (let at = 0, k = 0; at < stream.length; k++) {
            const n = cuts[k % cuts.length];
            rx.push(stream.subarray(at, at + n));
            at += n;
          }
          for (const e of errors) {
            expect(e).toBeInstanceOf(WireError);
            expect(CODES).toContain((e as WireError).code);
          }
          for (const p of packets) {
            const r = typedOutcome(() => decodePayload(p.typeCode, p.payload, ctx, p.seq));
            if (r.ok) expectEncoderAgrees(p.typeCode, r.value, ctx);
          }
        },
      ),
    );
  });
});
