/**
 * A link is a byte stream shaped like WebSerial's SerialPort once open: a
 * `readable` of Uint8Array chunks and a `writable` that accepts them (DESIGN.md
 * decision 6). WebSerial, web-serial-polyfill, Node's serialport and the simulator
 * all provide one; the runtime cannot tell them apart.
 */
/** The firmware's default serial rate (firmware MAXL_DEFAULT_BAUD); native-USB boards ignore it. */
export const MAXL_DEFAULT_BAUD = 250_000;

export interface Link {
  readonly readable: ReadableStream<Uint8Array>;
  readonly writable: WritableStream<Uint8Array>;
  /** A label for logs: a port name, or "sim:motorOne". */
  readonly label?: string;
  /** Closes the link; called by the runtime when a session ends. */
  close?(): Promise<void>;
}
