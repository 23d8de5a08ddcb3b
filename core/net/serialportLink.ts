/**
 * A link over Node's `serialport` package: a board on /dev/ttyACM0, COM3, or a
 * pseudo-terminal. It opens the port and offers its bytes as the same pair of web
 * streams WebSerial gives a page (link.ts), so a Node script drives real boards
 * with the same runtime:
 *
 *     const link = await openSerialportLink('/dev/ttyACM0');
 *     const maxl = createMAXL(config, { links: [link] });
 *     await maxl.begin();
 *
 * `serialport` is imported when a port is opened, so bundles for the browser never
 * load its native binding.
 */
import { MaxlError } from '../errors.ts';
import { MAXL_DEFAULT_BAUD, uartByteTime_us, uartBytesPerSecond, type Link } from './link.ts';

export interface SerialportLinkOptions {
  baudRate?: number;
  /**
   * Whether the board's processor takes its bytes from a UART behind a USB–serial
   * bridge (an Uno's 16U2, a CH340, an FTDI): then each byte takes 10 bits at the
   * baud rate, which clock sync counts (Link.uartByteTime_us). Default true, the
   * Uno; pass false for a native-USB board (Leonardo, Teensy, RP2040).
   */
  uart?: boolean;
}

/** Minimal shape of serialport's SerialPort that this adapter uses. */
interface NodePort {
  on(event: 'data', listener: (chunk: Buffer) => void): void;
  on(event: 'close' | 'error', listener: (err?: Error | null) => void): void;
  write(data: Uint8Array, callback: (err?: Error | null) => void): boolean;
  drain(callback: (err?: Error | null) => void): void;
  close(callback: (err?: Error | null) => void): void;
  readonly isOpen: boolean;
}

/** Opens `path` and resolves to a link once the port is open; a port that cannot be opened rejects with DEVICE_UNAVAILABLE. */
export async function openSerialportLink(path: string, options: SerialportLinkOptions = {}): Promise<Link> {
  const { SerialPort } = await import('serialport');
  const baudRate = options.baudRate ?? MAXL_DEFAULT_BAUD;
  const port = await new Promise<NodePort>((resolve, reject) => {
    const p: NodePort = new SerialPort({ path, baudRate, autoOpen: true }, (err) =>
      err ? reject(new MaxlError('DEVICE_UNAVAILABLE', `cannot open serial port ${path}: ${err.message}`, 'path')) : resolve(p),
    );
  });
  return serialportLink(port, path, uartBytesPerSecond(baudRate), options.uart === false ? undefined : uartByteTime_us(baudRate));
}

/** Wraps an open port. Reading ends when the port closes; closing the link closes the port. */
function serialportLink(port: NodePort, label: string, bytesPerSecond: number, byteTime_us: number | undefined): Link {
  let closed = false;
  const readable = new ReadableStream<Uint8Array>({
    start(controller) {
      port.on('data', (chunk) => {
        if (!closed) controller.enqueue(new Uint8Array(chunk.buffer, chunk.byteOffset, chunk.byteLength));
      });
      port.on('close', () => {
        if (closed) return;
        closed = true;
        controller.close();
      });
      port.on('error', (err) => {
        if (closed) return;
        closed = true;
        controller.error(err ?? new Error(`${label}: serial port error`));
      });
    },
    // The runtime cancels its reader when a session ends: drop what comes after.
    cancel() {
      closed = true;
    },
  });
  const writable = new WritableStream<Uint8Array>({
    // Resolves once the bytes have left for the device, so the stream's backpressure
    // follows the port's.
    write: (chunk) =>
      new Promise<void>((resolve, reject) => {
        port.write(chunk, (err) => (err ? reject(err) : port.drain((e) => (e ? reject(e) : resolve()))));
      }),
  });
  return {
    readable,
    writable,
    label,
    bytesPerSecond,
    uartByteTime_us: byteTime_us,
    close: () =>
      new Promise<void>((resolve) => {
        if (!port.isOpen) return resolve();
        port.close(() => resolve());
      }),
  };
}
