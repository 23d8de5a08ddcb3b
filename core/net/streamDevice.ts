/**
 * What the streamer needs of one device, and no more: whether it is open, how
 * long its round trips run, how long its oldest frame has waited for an ack, its
 * clock model, room for event entries, and a way to send a message.
 *
 * A `DeviceSession` (session.ts) is one; the runtime (core/runtime.ts) hands the
 * sessions to the streamer as StreamDevices, so the streamer never reaches into a
 * session's clock or counters.
 */
import type { ClockMap } from './clockMap.ts';
import type { Message } from './messages.ts';
import type { NackReasonName } from './protocol.ts';

/**
 * How a sent frame ended: acknowledged, or refused with a reason (the device
 * consumed it). `unsent` marks a frame the session gave up on when it ended (lost
 * or closed): the device may or may not have handled it.
 */
export type SendResult = { ok: true } | { ok: false; reason: NackReasonName; detail: number; unsent?: true };

export interface StreamDevice {
  /** Whether the session is open (not opening, lost or closed). */
  readonly isOpen: boolean;
  /** A high recent round trip (µs), 0 before any was measured. */
  readonly rttHigh_us: number;
  /** How long a frame waits for its ack before it is sent again (µs). */
  readonly resendAfter_us: number;
  /** The share of recent frames found corrupted (bad CRCs received, BAD_CRC nacks): 0 on a clean link. */
  readonly frameLoss: number;
  /** How long the oldest unacknowledged frame has waited since first sent (µs), 0 if none. */
  readonly oldestUnacked_us: number;
  /** Author µs → device µs, null until the clock model has a fit. */
  readonly clockMap: ClockMap | null;
  /**
   * Takes room for `count` event entries on the device, if it has that much free (as
   * it last reported, less what was taken since): true, and the room is spoken for;
   * false, and nothing changes.
   */
  takeEventRoom(count: number): boolean;
  /** The sequence number of the last message given to send() (recovery maps a device's next expected one back to the frames it handled). */
  readonly lastSentSeq: number;
  /** Sends a message reliably and in order; resolves once the device acknowledged or refused it. */
  send(message: Message): Promise<SendResult>;
}
