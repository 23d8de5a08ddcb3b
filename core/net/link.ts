/**
 * A link is a byte stream shaped like WebSerial's SerialPort once open: a
 * `readable` of Uint8Array chunks and a `writable` that accepts them (docs/design.md
 * decision 6). WebSerial, web-serial-polyfill, Node's serialport and the simulator
 * all provide one; the runtime cannot tell them apart.
 */
import { MaxlError } from '../errors.ts';

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

/**
 * µs one byte takes on a UART at `baud`: 10 bits (8N1), 40 µs at 250 000 baud. A
 * board whose USB reaches its processor through a USB–serial bridge (an Uno's 16U2,
 * a CH340, an FTDI) carries every byte over such a UART; a native-USB board
 * (Leonardo, Teensy, RP2040) has none, whatever baud the port is opened at.
 */
export function uartByteTime_us(baud: number): number {
  return 1e7 / baud;
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
  /**
   * µs each byte spends on a UART between the link and the device's processor
   * (uartByteTime_us), if there is one: set it for a USB–serial bridge (an Uno),
   * leave it out for a native-USB board and the simulator (whose links carry whole
   * USB frames at once). Clock sync counts each PING's and PONG's own bytes with it:
   * the two frames differ in length, so their wire times differ, and a two-way sync
   * that ignored them would be off by half the difference (clockSync.ts, "Frames
   * take time on a UART").
   */
  readonly uartByteTime_us?: number;
}

/** Refuses links whose declared figures cannot be used (before any is opened), naming the link and the field. */
export function checkLinks(links: readonly Link[]): void {
  links.forEach((link, i) => {
    const t = link.uartByteTime_us;
    if (t !== undefined && !(Number.isFinite(t) && t >= 0)) {
      throw new MaxlError('DEVICE_UNAVAILABLE', `link ${i} (${link.label ?? 'unnamed'}) declares uartByteTime_us ${t}: it must be a finite number of µs ≥ 0 (10 bits at the baud rate, uartByteTime_us(baud)), or left out for a native-USB board`, `links[${i}].uartByteTime_us`);
    }
  });
}
