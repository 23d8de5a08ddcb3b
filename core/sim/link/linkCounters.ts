/** What one direction of a simulated link did, since it was made. */
export interface LinkDirectionCounters {
  /** Bytes handed to the link by the sender. */
  bytesWritten: number;
  /** Bytes handed to the receiver (corrupted ones included). */
  bytesDelivered: number;
  /** Delivered bytes whose value the link changed. */
  bytesCorrupted: number;
  /** USB packets carried (lost ones included). */
  packetsSent: number;
  /** USB packets dropped whole, and the bytes they held. */
  packetsLost: number;
  bytesLost: number;
  /** Bytes dropped because the link was cut (written after the cut, or due after it). */
  bytesCut: number;
  /** USB frames that carried data in this direction. */
  framesUsed: number;
  /** Delay from a write to its delivery, µs, over every delivered chunk. */
  latencyMin_us: number;
  latencyMax_us: number;
  latencySum_us: number;
  /** Number of delivered chunks (one per write per frame); latencySum_us / chunksDelivered is the mean. */
  chunksDelivered: number;
}

export function emptyCounters(): LinkDirectionCounters {
  return {
    bytesWritten: 0,
    bytesDelivered: 0,
    bytesCorrupted: 0,
    packetsSent: 0,
    packetsLost: 0,
    bytesLost: 0,
    bytesCut: 0,
    framesUsed: 0,
    latencyMin_us: Infinity,
    latencyMax_us: -Infinity,
    latencySum_us: 0,
    chunksDelivered: 0,
  };
}
