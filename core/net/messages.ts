/**
 * Every message of the protocol as a typed object, and its payload encoding
 * (docs/protocol.md §4). Field names are the spec's.
 */
import { ByteReader, ByteWriter, WireFormatError } from './bytes.ts';
import { MessageType, nameOf, type MessageTypeName } from './protocol.ts';

export interface GeometrySegment {
  /** mm */
  length: number;
  /** each position slot at the segment's end, i32 in 2⁻¹⁶ units */
  p1: number[];
}

export interface TimingSegment {
  shape: number;
  /** device µs per phase */
  durations: number[];
  /** normalised path acceleration a/L, 1/s² */
  alpha: number;
}

export interface EventEntry {
  /** device µs after the segment's start */
  offset: number;
  value: number;
}

export interface SensorSample {
  /** device µs since the previous sample (0 for the first) */
  dt: number;
  values: number[];
}

export type Message =
  | { type: 'HELLO_REQUEST'; protocol: number }
  | { type: 'PING'; pingId: number; replyAfter: number }
  | { type: 'CLOCK'; deviceRef: number; authorRef: number; ratePpb: number }
  | { type: 'SUBSCRIBE'; reader: number; kind: number; slot: number }
  | { type: 'GEOMETRY'; firstId: number; count: number; flags: number; p0?: number[]; segments: GeometrySegment[] }
  | { type: 'TIMING'; firstId: number; count: number; flags: number; stopDecel: number; start?: number; segments: TimingSegment[] }
  | { type: 'EVENTS'; segmentId: number; slot: number; firstIndex: number; count: number; entries: EventEntry[] }
  | { type: 'REPLACE_TAIL'; fromId: number }
  | { type: 'HALT'; mode: number; at: number }
  | { type: 'STATUS_REQUEST' }
  | {
      type: 'HELLO';
      protocol: number;
      fwMajor: number;
      fwMinor: number;
      fwPatch: number;
      clockHz: number;
      segmentCapacity: number;
      eventCapacity: number;
      readerCount: number;
      name: string;
    }
  | { type: 'READER'; index: number; kind: number; channels: number; name: string }
  | { type: 'ACK'; ackSeq: number; freeSegments: number; freeEvents: number }
  | { type: 'NACK'; seq: number; reason: number; detail: number }
  | { type: 'PONG'; pingId: number; rxTime: number; txTime: number }
  | { type: 'STATUS'; now: number; state: number; segmentId: number; sigma: number; depth: number; flags: number }
  | { type: 'SAMPLES'; reader: number; sampleSeq: number; count: number; t0: number; samples: SensorSample[] };

export type MessageOf<T extends MessageTypeName> = Extract<Message, { type: T }>;

/** What a decoder must know that the bytes do not say. */
export interface DecodeContext {
  /** P, the number of position slots the device reads (GEOMETRY) */
  positionSlots: number;
  /** values per sample of the sensor reader (SAMPLES) */
  channels: number;
}

/** Number of phases a TIMING shape lists (up to the first 'none'). */
export function shapePhaseCount(shape: number): number {
  let n = 0;
  while (n < 3 && ((shape >> (2 * n)) & 3) !== 0) n++;
  return n;
}

export function encodePayload(m: Message): Uint8Array {
  const w = new ByteWriter();
  switch (m.type) {
    case 'HELLO_REQUEST':
      w.u8(m.protocol);
      break;
    case 'PING':
      w.u16(m.pingId).u16(m.replyAfter);
      break;
    case 'CLOCK':
      w.u32(m.deviceRef).u32(m.authorRef).i32(m.ratePpb);
      break;
    case 'SUBSCRIBE':
      w.u8(m.reader).u8(m.kind).u8(m.slot);
      break;
    case 'GEOMETRY':
      if (m.segments.length !== m.count) throw new WireFormatError('GEOMETRY count does not match its segments');
      w.u16(m.firstId).u8(m.count).u8(m.flags);
      if (m.flags & 1) for (const p of m.p0 ?? []) w.i32(p);
      for (const s of m.segments) {
        w.f32(s.length);
        for (const p of s.p1) w.i32(p);
      }
      break;
    case 'TIMING':
      if (m.segments.length !== m.count) throw new WireFormatError('TIMING count does not match its segments');
      w.u16(m.firstId).u8(m.count).u8(m.flags).f32(m.stopDecel);
      if (m.flags & 1) w.u32(m.start ?? 0);
      for (const s of m.segments) {
        if (s.durations.length !== shapePhaseCount(s.shape)) throw new WireFormatError('TIMING durations do not match the shape');
        w.u8(s.shape);
        for (const d of s.durations) w.varint(d);
        w.f32(s.alpha);
      }
      break;
    case 'EVENTS':
      if (m.entries.length !== m.count) throw new WireFormatError('EVENTS count does not match its entries');
      w.u16(m.segmentId).u8(m.slot).u16(m.firstIndex).u8(m.count);
      for (const e of m.entries) w.varint(e.offset).f32(e.value);
      break;
    case 'REPLACE_TAIL':
      w.u16(m.fromId);
      break;
    case 'HALT':
      w.u8(m.mode).u32(m.at);
      break;
    case 'STATUS_REQUEST':
      break;
    case 'HELLO':
      w.u8(m.protocol).u8(m.fwMajor).u8(m.fwMinor).u8(m.fwPatch).u32(m.clockHz).u8(m.segmentCapacity).u8(m.eventCapacity).u8(m.readerCount).str(m.name);
      break;
    case 'READER':
      w.u8(m.index).u8(m.kind).u8(m.channels).str(m.name);
      break;
    case 'ACK':
      w.u8(m.ackSeq).u8(m.freeSegments).u8(m.freeEvents);
      break;
    case 'NACK':
      w.u8(m.seq).u8(m.reason).u16(m.detail);
      break;
    case 'PONG':
      w.u16(m.pingId).u32(m.rxTime).u32(m.txTime);
      break;
    case 'STATUS':
      w.u32(m.now).u8(m.state).u16(m.segmentId).f32(m.sigma).u8(m.depth).u8(m.flags);
      break;
    case 'SAMPLES':
      if (m.samples.length !== m.count) throw new WireFormatError('SAMPLES count does not match its samples');
      w.u8(m.reader).u16(m.sampleSeq).u8(m.count).u32(m.t0);
      for (const s of m.samples) {
        w.varint(s.dt);
        for (const v of s.values) w.f32(v);
      }
      break;
  }
  return w.bytes();
}

/** The error codes a received frame can fail with (docs/protocol.md §3 and §4). */
export type WireErrorCode = 'TOO_LONG' | 'BAD_COBS' | 'TOO_SHORT' | 'BAD_CRC' | 'MALFORMED' | 'UNKNOWN_MESSAGE';

export class WireError extends Error {
  constructor(
    readonly code: WireErrorCode,
    message: string,
    /** for MALFORMED and UNKNOWN_MESSAGE: the packet's seq and type */
    readonly seq?: number,
    readonly typeCode?: number,
  ) {
    super(message);
    this.name = 'WireError';
  }
}

export function decodePayload(typeCode: number, payload: Uint8Array, ctx: DecodeContext, seq = 0): Message {
  const type = nameOf(MessageType, typeCode);
  if (type === undefined) throw new WireError('UNKNOWN_MESSAGE', `unknown message type 0x${typeCode.toString(16)}`, seq, typeCode);
  const r = new ByteReader(payload);
  try {
    const m = readMessage(type, r, ctx);
    r.done();
    return m;
  } catch (err) {
    if (err instanceof WireFormatError) throw new WireError('MALFORMED', `${type}: ${err.message}`, seq, typeCode);
    throw err;
  }
}

function readMessage(type: MessageTypeName, r: ByteReader, ctx: DecodeContext): Message {
  switch (type) {
    case 'HELLO_REQUEST':
      return { type, protocol: r.u8() };
    case 'PING':
      return { type, pingId: r.u16(), replyAfter: r.u16() };
    case 'CLOCK':
      return { type, deviceRef: r.u32(), authorRef: r.u32(), ratePpb: r.i32() };
    case 'SUBSCRIBE':
      return { type, reader: r.u8(), kind: r.u8(), slot: r.u8() };
    case 'GEOMETRY': {
      const firstId = r.u16();
      const count = r.u8();
      const flags = r.u8();
      const slots = ctx.positionSlots;
      const m: MessageOf<'GEOMETRY'> = { type, firstId, count, flags, segments: [] };
      if (flags & 1) m.p0 = Array.from({ length: slots }, () => r.i32());
      for (let k = 0; k < count; k++) m.segments.push({ length: r.f32(), p1: Array.from({ length: slots }, () => r.i32()) });
      return m;
    }
    case 'TIMING': {
      const firstId = r.u16();
      const count = r.u8();
      const flags = r.u8();
      const stopDecel = r.f32();
      const m: MessageOf<'TIMING'> = { type, firstId, count, flags, stopDecel, segments: [] };
      if (flags & 1) m.start = r.u32();
      for (let k = 0; k < count; k++) {
        const shape = r.u8();
        const phases = shapePhaseCount(shape);
        if (phases === 0 || shape >> (2 * phases) !== 0) throw new WireFormatError(`bad shape 0x${shape.toString(16)}`);
        const durations = Array.from({ length: shapePhaseCount(shape) }, () => r.varint());
        m.segments.push({ shape, durations, alpha: r.f32() });
      }
      return m;
    }
    case 'EVENTS': {
      const segmentId = r.u16();
      const slot = r.u8();
      const firstIndex = r.u16();
      const count = r.u8();
      const entries: EventEntry[] = [];
      for (let k = 0; k < count; k++) entries.push({ offset: r.varint(), value: r.f32() });
      return { type, segmentId, slot, firstIndex, count, entries };
    }
    case 'REPLACE_TAIL':
      return { type, fromId: r.u16() };
    case 'HALT':
      return { type, mode: r.u8(), at: r.u32() };
    case 'STATUS_REQUEST':
      return { type };
    case 'HELLO':
      return {
        type,
        protocol: r.u8(),
        fwMajor: r.u8(),
        fwMinor: r.u8(),
        fwPatch: r.u8(),
        clockHz: r.u32(),
        segmentCapacity: r.u8(),
        eventCapacity: r.u8(),
        readerCount: r.u8(),
        name: r.str(),
      };
    case 'READER':
      return { type, index: r.u8(), kind: r.u8(), channels: r.u8(), name: r.str() };
    case 'ACK':
      return { type, ackSeq: r.u8(), freeSegments: r.u8(), freeEvents: r.u8() };
    case 'NACK':
      return { type, seq: r.u8(), reason: r.u8(), detail: r.u16() };
    case 'PONG':
      return { type, pingId: r.u16(), rxTime: r.u32(), txTime: r.u32() };
    case 'STATUS':
      return { type, now: r.u32(), state: r.u8(), segmentId: r.u16(), sigma: r.f32(), depth: r.u8(), flags: r.u8() };
    case 'SAMPLES': {
      const reader = r.u8();
      const sampleSeq = r.u16();
      const count = r.u8();
      const t0 = r.u32();
      const samples: SensorSample[] = [];
      for (let k = 0; k < count; k++) samples.push({ dt: r.varint(), values: Array.from({ length: ctx.channels }, () => r.f32()) });
      return { type, reader, sampleSeq, count, t0, samples };
    }
  }
}
