/**
 * A link is a byte stream shaped like WebSerial's SerialPort once open: a
 * `readable` of Uint8Array chunks and a `writable` that accepts them (docs/design.md
 * decision 6). WebSerial, web-serial-polyfill, Node's serialport and the simulator
 * all provide one; the runtime cannot tell them apart.
 */
/** The firmware's default serial rate (firmware MAXL_DEFAULT_BAUD); native-USB boards ignore it. */
export const MAXL_DEFAULT_BAUD = 250_000;

/**
 * Bytes per second a UART carries at `baud`: 8N1 framing puts 10 bits on the wire
 * per byte (a start bit, 8 data bits, a stop bit). An Uno's USB bridge feeds its
 * ATmega328P through such a UART, so this is what reaches the board, whatever USB
 * carries before it.
 */
export function uartBytesPerSecond(baud: number): number {
  return baud / 10;
}

export interface Link {
  readonly readable: ReadableStream<Uint8Array>;
  readonly writable: WritableStream<Uint8Array>;
  /** A label for logs: a port name, or "sim:motorOne". */
  readonly label?: string;
  /** Closes the link; called by the runtime when a session ends. */
  close?(): Promise<void>;
  /**
   * Bytes per second the link carries to the device, if known. The runtime keeps
   * the planned motion within it (linkFeedLimit.ts): a job that needs more
   * would starve the device.
   */
  readonly bytesPerSecond?: number;
}
