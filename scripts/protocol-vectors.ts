/**
 * The shared test vectors of the wire protocol: docs/protocol-vectors.json.
 * Both the TypeScript tests (core/net/vectors.test.ts) and the C++ tests
 * (firmware/test) load that one file, so the two codecs cannot drift apart.
 *
 *   npx tsx scripts/protocol-vectors.ts          rewrites the file
 *   npx tsx scripts/protocol-vectors.ts --check  fails if it is out of date
 *
 * Valid vectors are encoded with the TypeScript codec; the TypeScript tests
 * separately check that codec against hand-assembled bytes and known COBS and CRC
 * values, so the file does not merely agree with itself. Every f32 here is exactly
 * representable, so JSON numbers compare exactly.
 */
import { readFileSync, writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { cobsEncode } from '../core/net/cobs.ts';
import { crc16 } from '../core/net/crc16.ts';
import { encodeFrame } from '../core/net/frame.ts';
import type { Message } from '../core/net/messages.ts';
import { PROTOCOL_VERSION } from '../core/net/protocol.ts';

export const VECTORS_PATH = fileURLToPath(new URL('../docs/protocol-vectors.json', import.meta.url));

interface Context {
  positionSlots: number;
  channels: number;
}

export interface Vector {
  name: string;
  frame: string;
  context: Context;
  packet?: { seq: number; type: string; fields: Record<string, unknown> };
  error?: string;
}

const hex = (b: Uint8Array) => Buffer.from(b).toString('hex');
const ctx = (positionSlots = 0, channels = 0): Context => ({ positionSlots, channels });

function valid(name: string, seq: number, message: Message, context = ctx()): Vector {
  const { type, ...fields } = message;
  return { name, frame: hex(encodeFrame(seq, message)), context, packet: { seq, type, fields } };
}

/** A frame around arbitrary packet bytes, with a correct CRC unless told otherwise. */
function rawFrame(packetWithoutCrc: number[], crcDelta = 0): Uint8Array {
  const p = Uint8Array.from(packetWithoutCrc);
  const crc = (crc16(p) + crcDelta) & 0xffff;
  const packet = Uint8Array.from([...p, crc & 0xff, crc >> 8]);
  return Uint8Array.from([...cobsEncode(packet), 0]);
}

function invalid(name: string, frame: Uint8Array, error: string, context = ctx()): Vector {
  return { name, frame: hex(frame), context, error };
}

export function buildVectors(): { protocol: number; vectors: Vector[] } {
  const v: Vector[] = [
    valid('hello request', 0, { type: 'HELLO_REQUEST', protocol: PROTOCOL_VERSION }),
    valid('ping', 5, { type: 'PING', pingId: 0x0102, replyAfter: 1500 }),
    valid('ping whose packet holds zeros (COBS at work)', 0, { type: 'PING', pingId: 0, replyAfter: 0 }),
    valid('clock with a negative rate', 17, { type: 'CLOCK', deviceRef: 0xfffffff0, authorRef: 123456789, ratePpb: -150000 }),
    valid('subscribe', 2, { type: 'SUBSCRIBE', reader: 1, kind: 1, slot: 0 }),
    valid(
      'geometry, two slots, with p0',
      3,
      {
        type: 'GEOMETRY',
        firstId: 1,
        count: 2,
        flags: 1,
        p0: [0, -65536],
        segments: [
          { length: 10.5, p1: [688128, -65536] },
          { length: 0.25, p1: [688128, -49152] },
        ],
      },
      ctx(2),
    ),
    valid('geometry, one slot, continuing', 4, { type: 'GEOMETRY', firstId: 65535, count: 1, flags: 0, segments: [{ length: 1, p1: [2147483647] }] }, ctx(1)),
    valid('geometry, no position slots (a velocity-only device)', 9, { type: 'GEOMETRY', firstId: 7, count: 1, flags: 0, segments: [{ length: 3.5, p1: [] }] }, ctx(0)),
    valid('timing, trapezoid with a start, varints of 1 to 5 bytes', 6, {
      type: 'TIMING',
      firstId: 1,
      count: 2,
      flags: 1,
      stopDecel: 3000,
      start: 4000000000,
      segments: [
        { shape: 0b11_10_01, durations: [127, 128, 16384], alpha: 1500.5 },
        { shape: 0b11, durations: [4294967295], alpha: -0.5 },
      ],
    }),
    valid('timing, contiguous cruise', 7, { type: 'TIMING', firstId: 3, count: 1, flags: 0, stopDecel: 250.25, segments: [{ shape: 0b10, durations: [2097152], alpha: 0 }] }),
    // A dwell: a segment of length 0 that holds its start (p1 = the p1 before it), timed as one
    // phase at alpha 0 lasting the dwell; an event-only move is an instant, a dwell of 0 µs.
    valid(
      'geometry, a dwell between two segments (length 0, p1 = where it starts)',
      13,
      {
        type: 'GEOMETRY',
        firstId: 20,
        count: 3,
        flags: 0,
        segments: [
          { length: 2.5, p1: [163840] },
          { length: 0, p1: [163840] },
          { length: 2.5, p1: [327680] },
        ],
      },
      ctx(1),
    ),
    valid('timing, a 120 ms dwell then an instant (0 µs)', 14, {
      type: 'TIMING',
      firstId: 21,
      count: 2,
      flags: 0,
      stopDecel: 1500,
      segments: [
        { shape: 0b10, durations: [120000], alpha: 0 },
        { shape: 0b10, durations: [0], alpha: 0 },
      ],
    }),
    valid('events with a continuation index', 8, {
      type: 'EVENTS',
      segmentId: 3,
      slot: 0,
      firstIndex: 2,
      count: 3,
      entries: [
        { offset: 0, value: 255 },
        { offset: 10000, value: 0 },
        { offset: 20000, value: 0.75 },
      ],
    }),
    valid('replace tail', 10, { type: 'REPLACE_TAIL', fromId: 42 }),
    valid('halt now', 11, { type: 'HALT', mode: 0, at: 0 }),
    valid('halt braking at a time', 12, { type: 'HALT', mode: 1, at: 99999 }),
    valid('status request', 255, { type: 'STATUS_REQUEST' }),
    valid('hello', 0, {
      type: 'HELLO',
      protocol: PROTOCOL_VERSION,
      fwMajor: 0,
      fwMinor: 3,
      fwPatch: 1,
      clockHz: 1000000,
      segmentCapacity: 12,
      eventCapacity: 16,
      readerCount: 2,
      name: 'motorOne',
    }),
    valid('reader', 1, { type: 'READER', index: 1, kind: 5, channels: 3, name: 'accel' }),
    valid('ack', 2, { type: 'ACK', ackSeq: 6, freeSegments: 10, freeEvents: 16 }),
    valid('nack, late segment', 3, { type: 'NACK', seq: 7, reason: 4, detail: 3 }),
    valid('nack, clock jump', 4, { type: 'NACK', seq: 8, reason: 11, detail: 513 }),
    valid('pong', 4, { type: 'PONG', pingId: 0x0102, rxTime: 1000, txTime: 1012 }),
    valid('status, braking', 5, { type: 'STATUS', now: 123456, state: 2, segmentId: 9, sigma: 0.5, depth: 3, flags: 1 }),
    valid('status, clock jump while running', 6, { type: 'STATUS', now: 4294967000, state: 1, segmentId: 10, sigma: 0.75, depth: 4, flags: 16 }),
    valid(
      'samples, three channels',
      6,
      {
        type: 'SAMPLES',
        reader: 1,
        sampleSeq: 300,
        count: 2,
        t0: 5000,
        samples: [
          { dt: 0, values: [0.5, -9810, 1] },
          { dt: 1000, values: [1.5, -9809.5, 0] },
        ],
      },
      ctx(0, 3),
    ),
  ];

  const ping = encodeFrame(5, { type: 'PING', pingId: 0x0102, replyAfter: 1500 });
  const flipped = Uint8Array.from(ping);
  flipped[3] ^= 0x01; // a data byte; COBS stays valid, the CRC does not
  v.push(
    invalid('crc mismatch', flipped, 'BAD_CRC'),
    invalid('crc off by one', rawFrame([5, 0x02, 0x02, 0x01], 1), 'BAD_CRC'),
    invalid('cobs code byte points past the end', Uint8Array.from([0x05, 0x01, 0x02, 0x00]), 'BAD_COBS'),
    invalid('packet shorter than 4 bytes', Uint8Array.from([0x04, 0x01, 0x02, 0x03, 0x00]), 'TOO_SHORT'),
    invalid('more than 65 bytes before a delimiter', Uint8Array.from([...new Array(70).fill(0x11), 0x00]), 'TOO_LONG'),
    invalid('unknown message type', rawFrame([1, 0x30]), 'UNKNOWN_MESSAGE'),
    invalid('unknown device-bound type', rawFrame([1, 0x7f, 1, 2]), 'UNKNOWN_MESSAGE'),
    invalid('ping payload too short (the 2-byte ping of an early draft)', rawFrame([1, 0x02, 0x01, 0x02]), 'MALFORMED'),
    invalid('ping with a byte left over', rawFrame([1, 0x02, 0x01, 0x02, 0xdc, 0x05, 0x03]), 'MALFORMED'),
    invalid('timing with a six-byte varint', rawFrame([1, 0x06, 1, 0, 1, 0, 0, 0, 0x80, 0x3f, 0b10, 0x80, 0x80, 0x80, 0x80, 0x80, 0x01, 0, 0, 0, 0]), 'MALFORMED'),
    invalid('timing with a varint over 32 bits', rawFrame([1, 0x06, 1, 0, 1, 0, 0, 0, 0x80, 0x3f, 0b10, 0xff, 0xff, 0xff, 0xff, 0x1f, 0, 0, 0, 0]), 'MALFORMED'),
    invalid('timing with an empty shape', rawFrame([1, 0x06, 1, 0, 1, 0, 0, 0, 0x80, 0x3f, 0, 0, 0, 0, 0]), 'MALFORMED'),
    invalid('timing with a phase after the end of the list', rawFrame([1, 0x06, 1, 0, 1, 0, 0, 0, 0x80, 0x3f, 0b10_00_10, 5, 0, 0, 0, 0]), 'MALFORMED'),
    invalid('geometry shorter than its count', rawFrame([1, 0x05, 1, 0, 2, 0, 0, 0, 0x80, 0x3f, 1, 0, 0, 0]), 'MALFORMED', ctx(1)),
    invalid('hello with a name over 31 bytes', rawFrame([0, 0x41, 1, 0, 0, 1, 0x40, 0x42, 0x0f, 0, 8, 8, 0, 32, ...new Array(32).fill(0x61)]), 'MALFORMED'),
  );
  return { protocol: PROTOCOL_VERSION, vectors: v };
}

export function vectorsJson(): string {
  return `${JSON.stringify(buildVectors(), null, 2)}\n`;
}

if (process.argv[1] && fileURLToPath(import.meta.url) === process.argv[1]) {
  const text = vectorsJson();
  if (process.argv.includes('--check')) {
    if (readFileSync(VECTORS_PATH, 'utf8') !== text) {
      console.error(`${VECTORS_PATH} is out of date: run npx tsx scripts/protocol-vectors.ts`);
      process.exit(1);
    }
    console.log('protocol vectors up to date');
  } else {
    writeFileSync(VECTORS_PATH, text);
    console.log(`wrote ${buildVectors().vectors.length} vectors to ${VECTORS_PATH}`);
  }
}
