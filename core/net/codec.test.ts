import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import fc from 'fast-check';
import { cobsDecode, cobsEncode } from './cobs.ts';
import { crc16 } from './crc16.ts';
import { decodeFrame, encodeFrame, FrameReceiver, type RawPacket } from './frame.ts';
import { WireError, type Message } from './messages.ts';
import { buildVectors, VECTORS_PATH, vectorsJson, type Vector } from '../../scripts/protocol-vectors.ts';

const bytes = (hex: string) => Uint8Array.from(Buffer.from(hex.replace(/\s/g, ''), 'hex'));
const hex = (b: Uint8Array) => Buffer.from(b).toString('hex');

describe('CRC-16/CCITT-FALSE', () => {
  it('gives the standard check value', () => {
    expect(crc16(new TextEncoder().encode('123456789'))).toBe(0x29b1);
    expect(crc16(new Uint8Array(0))).toBe(0xffff);
  });
});

describe('COBS', () => {
  // The examples of the COBS article (Cheshire and Baker; Wikipedia's table).
  const range = (a: number, b: number) => Array.from({ length: b - a + 1 }, (_, i) => a + i);
  it.each([
    [[0x00], [0x01, 0x01]],
    [[0x00, 0x00], [0x01, 0x01, 0x01]],
    [[0x00, 0x11, 0x00], [0x01, 0x02, 0x11, 0x01]],
    [[0x11, 0x22, 0x00, 0x33], [0x03, 0x11, 0x22, 0x02, 0x33]],
    [[0x11, 0x22, 0x33, 0x44], [0x05, 0x11, 0x22, 0x33, 0x44]],
    [[0x11, 0x00, 0x00, 0x00], [0x02, 0x11, 0x01, 0x01, 0x01]],
    [range(0x01, 0xfe), [0xff, ...range(0x01, 0xfe)]],
    [[0x00, ...range(0x01, 0xfe)], [0x01, 0xff, ...range(0x01, 0xfe)]],
    [range(0x01, 0xff), [0xff, ...range(0x01, 0xfe), 0x02, 0xff]],
    [[...range(0x02, 0xff), 0x00], [0xff, ...range(0x02, 0xff), 0x01, 0x01]],
  ])('encodes example %#', (data, encoded) => {
    expect(Array.from(cobsEncode(Uint8Array.from(data)))).toEqual(encoded);
    expect(Array.from(cobsDecode(Uint8Array.from(encoded))!)).toEqual(data);
  });

  it('round-trips any bytes, and never emits a zero', () => {
    fc.assert(
      fc.property(fc.uint8Array({ maxLength: 600 }), (data) => {
        const enc = cobsEncode(data);
        expect(enc.includes(0)).toBe(false);
        expect(enc.length).toBeLessThanOrEqual(data.length + Math.ceil(data.length / 254) + 1);
        expect(Array.from(cobsDecode(enc)!)).toEqual(Array.from(data));
      }),
    );
  });
});

describe('frames', () => {
  it('matches a PING frame assembled by hand (CRC from Python binascii.crc_hqx)', () => {
    // seq 5, type 0x02, pingId 0x0102 and replyAfter 1500 little-endian, CRC 0xD325 little-endian,
    // COBS code 9, delimiter.
    expect(hex(encodeFrame(5, { type: 'PING', pingId: 0x0102, replyAfter: 1500 }))).toBe('0905020201dc0525d300');
    expect(decodeFrame(bytes('0905020201dc0525d300'), { positionSlots: 0, channels: 0 })).toEqual({ seq: 5, message: { type: 'PING', pingId: 0x0102, replyAfter: 1500 } });
  });

  it('refuses to build a packet over 64 bytes', () => {
    const segments = Array.from({ length: 6 }, () => ({ length: 1, p1: [1, 2] }));
    expect(() => encodeFrame(0, { type: 'GEOMETRY', firstId: 0, count: 6, flags: 0, segments })).toThrow(/exceeds/);
  });
});

describe('shared vectors (docs/protocol-vectors.json)', () => {
  const file = JSON.parse(readFileSync(VECTORS_PATH, 'utf8')) as { protocol: number; vectors: Vector[] };

  it('is what scripts/protocol-vectors.ts generates', () => {
    expect(readFileSync(VECTORS_PATH, 'utf8')).toBe(vectorsJson());
    expect(file.vectors.length).toBe(buildVectors().vectors.length);
  });

  it('covers every message type and every receive error', () => {
    const types = new Set(file.vectors.filter((v) => v.packet).map((v) => v.packet!.type));
    expect([...types].sort()).toEqual(
      ['ACK', 'CLOCK', 'EVENTS', 'GEOMETRY', 'HALT', 'HELLO', 'HELLO_REQUEST', 'NACK', 'PING', 'PONG', 'READER', 'REPLACE_TAIL', 'SAMPLES', 'STATUS', 'STATUS_REQUEST', 'SUBSCRIBE', 'TIMING'].sort(),
    );
    const errors = new Set(file.vectors.filter((v) => v.error).map((v) => v.error));
    expect([...errors].sort()).toEqual(['BAD_COBS', 'BAD_CRC', 'MALFORMED', 'TOO_LONG', 'TOO_SHORT', 'UNKNOWN_MESSAGE']);
  });

  for (const v of file.vectors) {
    it(`${v.error ? 'rejects' : 'decodes and encodes'}: ${v.name}`, () => {
      const frame = bytes(v.frame);
      if (v.error) {
        let caught: unknown;
        try {
          decodeFrame(frame, v.context);
        } catch (err) {
          caught = err;
        }
        expect(caught).toBeInstanceOf(WireError);
        expect((caught as WireError).code).toBe(v.error);
        return;
      }
      const p = v.packet!;
      const message = { type: p.type, ...p.fields } as Message;
      expect(decodeFrame(frame, v.context)).toEqual({ seq: p.seq, message });
      expect(hex(encodeFrame(p.seq, message))).toBe(v.frame);
    });
  }
});

describe('FrameReceiver', () => {
  it('splits a stream, however it is chunked, dropping bad frames and reporting why', () => {
    const file = JSON.parse(readFileSync(VECTORS_PATH, 'utf8')) as { vectors: Vector[] };
    const stream = Buffer.concat([Buffer.from([0x00]), ...file.vectors.map((v) => Buffer.from(v.frame, 'hex'))]);
    const expectedPackets = file.vectors.filter((v) => v.packet || v.error === 'MALFORMED' || v.error === 'UNKNOWN_MESSAGE').length;
    const expectedErrors = file.vectors.filter((v) => ['BAD_CRC', 'BAD_COBS', 'TOO_SHORT', 'TOO_LONG'].includes(v.error ?? '')).map((v) => v.error);
    fc.assert(
      fc.property(fc.array(fc.integer({ min: 1, max: 40 }), { minLength: 1, maxLength: 200 }), (cuts) => {
        const packets: RawPacket[] = [];
        const errors: string[] = [];
        const rx = new FrameReceiver((p) => packets.push(p), (e) => errors.push(e.code));
        let at = 0;
        for (let k = 0; at < stream.length; k++) {
          const n = cuts[k % cuts.length];
          rx.push(Uint8Array.from(stream.subarray(at, at + n)));
          at += n;
        }
        expect(packets.length).toBe(expectedPackets);
        expect(errors).toEqual(expectedErrors);
      }),
      { numRuns: 50 },
    );
  });
});
