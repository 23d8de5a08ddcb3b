/**
 * Boards over Web Serial. "Add device" asks the browser for a port (this needs the
 * user's click, so it runs on the page), opens it, and hands its two streams to the
 * worker, which runs the session. Without navigator.serial but with WebUSB, the
 * web-serial-polyfill drives USB CDC boards; with neither, the page says what is
 * needed.
 */
/// <reference types="w3c-web-serial" />

import { MAXL_DEFAULT_BAUD, uartBytesPerSecond } from '../../core/net/link.ts';

/** What navigator.serial offers, and what the polyfill offers in its place. */
export interface SerialApi {
  requestPort(options?: SerialPortRequestOptions): Promise<SerialPortLike>;
  getPorts(): Promise<SerialPortLike[]>;
}

export interface SerialPortLike {
  readonly readable: ReadableStream<Uint8Array> | null;
  readonly writable: WritableStream<Uint8Array> | null;
  open(options: SerialOptions): Promise<void>;
  close(): Promise<void>;
  getInfo(): Partial<SerialPortInfo>;
}

export type SerialSupport =
  | { kind: 'native'; api: SerialApi }
  | { kind: 'polyfill'; api: SerialApi }
  | { kind: 'none'; reason: string };

/** Web Serial if the browser has it, else web-serial-polyfill over WebUSB, else why neither works. */
export async function serialSupport(): Promise<SerialSupport> {
  const nav = navigator as Navigator & { serial?: SerialApi; usb?: unknown };
  if (nav.serial) return { kind: 'native', api: nav.serial };
  if (nav.usb) {
    const polyfill = await import('web-serial-polyfill');
    return { kind: 'polyfill', api: polyfill.serial as unknown as SerialApi };
  }
  return { kind: 'none', reason: unsupportedReason() };
}

export function unsupportedReason(): string {
  const secure = window.isSecureContext;
  const base = 'Connecting boards needs Web Serial (or WebUSB): use Chrome or Edge on a desktop computer';
  if (!secure) {
    return `${base}, and open the workbench over https or at http://localhost — this page (${location.origin}) is not a secure context, so the browser hides serial ports from it.`;
  }
  return `${base}. This browser offers neither (Firefox and Safari do not, nor do phones). The simulated machines work everywhere.`;
}

export function portLabel(port: SerialPortLike): string {
  const info = port.getInfo();
  if (info.usbVendorId === undefined) return 'serial port';
  const hex = (n: number | undefined) => (n ?? 0).toString(16).padStart(4, '0');
  return `USB ${hex(info.usbVendorId)}:${hex(info.usbProductId)}`;
}

export interface OpenedPort {
  label: string;
  readable: ReadableStream<Uint8Array>;
  writable: WritableStream<Uint8Array>;
  /** What reaches the board: its UART at the baud the port runs at (native-USB boards take more). */
  bytesPerSecond: number;
}

/** Opens a port (if it is not open yet) and returns its streams, ready to transfer to the worker. */
export async function openPort(port: SerialPortLike): Promise<OpenedPort> {
  if (!port.readable || !port.writable) await port.open({ baudRate: MAXL_DEFAULT_BAUD });
  const { readable, writable } = port;
  if (!readable || !writable) throw new Error(`${portLabel(port)} opened without streams`);
  return { label: portLabel(port), readable, writable, bytesPerSecond: uartBytesPerSecond(MAXL_DEFAULT_BAUD) };
}

/** Words for a failed requestPort/open that a user can act on. */
export function connectErrorWords(err: unknown): string {
  const e = err as { name?: string; message?: string };
  if (e.name === 'NotFoundError') return 'No port was chosen.';
  if (e.name === 'SecurityError') return `The browser refused access to serial ports: ${e.message}. ${unsupportedReason()}`;
  if (e.name === 'InvalidStateError') return `The port is already open elsewhere (another tab, or the Arduino IDE's serial monitor): close it there and try again.`;
  if (e.name === 'NetworkError') return `The port could not be opened: ${e.message}. Unplug the board, plug it back in and try again.`;
  return `Could not connect: ${e.message ?? String(err)}`;
}
