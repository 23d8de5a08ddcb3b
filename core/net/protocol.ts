/**
 * Constants of the MAXL wire protocol, version 1 (docs/protocol.md).
 */
export const PROTOCOL_VERSION = 1;

/** A packet (seq, type, payload, crc) is at most this long; a payload at most 60. */
export const MAX_PACKET = 64;
export const MAX_PAYLOAD = MAX_PACKET - 4;
/** COBS adds one byte per 254; a frame on the wire adds the 0x00 delimiter. */
export const MAX_ENCODED = MAX_PACKET + 1;

/** Position values travel as i32 in units of 2⁻¹⁶ of the track's unit. */
export const POSITION_SCALE = 65536;

export const MessageType = {
  HELLO_REQUEST: 0x01,
  PING: 0x02,
  CLOCK: 0x03,
  SUBSCRIBE: 0x04,
  GEOMETRY: 0x05,
  TIMING: 0x06,
  EVENTS: 0x07,
  REPLACE_TAIL: 0x08,
  HALT: 0x09,
  STATUS_REQUEST: 0x0a,
  HELLO: 0x41,
  READER: 0x42,
  ACK: 0x43,
  NACK: 0x44,
  PONG: 0x45,
  STATUS: 0x46,
  SAMPLES: 0x47,
} as const;
export type MessageTypeName = keyof typeof MessageType;

export const ReaderKind = { position: 1, velocity: 2, acceleration: 3, event: 4, sensor: 5 } as const;
export type ReaderKindName = keyof typeof ReaderKind;

export const NackReason = {
  BAD_CRC: 1,
  UNKNOWN_MESSAGE: 2,
  QUEUE_FULL: 3,
  LATE_SEGMENT: 4,
  ALREADY_STARTED: 5,
  BAD_SUBSCRIPTION: 6,
  VERSION_MISMATCH: 7,
  OUT_OF_ORDER: 8,
  MALFORMED: 9,
  UNKNOWN_SEGMENT: 10,
  /** TIMING refused after the device's clock jumped (STATUS flag clockJump), until a new session. */
  CLOCK_JUMP: 11,
} as const;
export type NackReasonName = keyof typeof NackReason;

/** NACK OUT_OF_ORDER with this detail: the device has no session (before HELLO_REQUEST, or after a restart). */
export const NO_SESSION_DETAIL = 0x100;

export const DeviceState = { idle: 0, running: 1, braking: 2, stopped: 3, halted: 4 } as const;
export type DeviceStateName = keyof typeof DeviceState;

/** STATUS flags. */
export const StatusFlag = { starved: 1, late: 2, queueFull: 4, eventOverflow: 8, clockJump: 16 } as const;

/** GEOMETRY flags bit 0 and TIMING flags bit 0. */
export const HAS_P0 = 1;
export const HAS_START = 1;

/** TIMING phase shapes, two bits per phase from the low bits up. */
export const PhaseShape = { none: 0, accelerate: 1, cruise: 2, decelerate: 3 } as const;

export function nameOf<T extends Record<string, number>>(table: T, code: number): keyof T | undefined {
  for (const key of Object.keys(table)) if (table[key] === code) return key as keyof T;
  return undefined;
}
