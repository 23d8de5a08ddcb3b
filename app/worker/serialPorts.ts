/**
 * Serial ports as both the page and the worker see them: Web Serial's
 * `navigator.serial`, or web-serial-polyfill's `serial` over WebUSB in its place.
 * Nothing here touches `window`, so the MAXL worker runs it too.
 *
 * A port object cannot be sent from the page to a worker (it is not
 * serializable), but both see the same granted ports through `getPorts()`. So the
 * page names the port it was given by a `PortKey`, and the worker finds it among
 * its own `getPorts()` (findGrantedPort).
 */
/// <reference types="w3c-web-serial" />

import { MAXL_DEFAULT_BAUD, uartBytesPerSecond } from '../../core/net/link.ts';
import { portUartByteTime_us } from './uartBridges.ts';

/** What navigator.serial offers (the page's `requestPort` included), and what the polyfill offers in its place. */
export interface SerialApi {
  requestPort(options?: SerialPortRequestOptions): Promise<SerialPortLike>;
  getPorts(): Promise<SerialPortLike[]>;
}

/** A worker's navigator.serial has no `requestPort` (it needs a user's click on a page). */
export type GrantedPorts = Pick<SerialApi, 'getPorts'>;

export interface SerialPortLike {
  readonly readable: ReadableStream<Uint8Array> | null;
  readonly writable: WritableStream<Uint8Array> | null;
  open(options: SerialOptions): Promise<void>;
  close(): Promise<void>;
  getInfo(): Partial<SerialPortInfo>;
}

/** Where a port's bytes come from: Web Serial, or web-serial-polyfill over WebUSB. */
export type PortApi = 'serial' | 'usb';

/**
 * A granted port, named so that another context (the worker) can find it: its USB
 * ids, and its place among the granted ports with those ids (`ordinal`), or null
 * when the page could not tell (the polyfill makes new port objects on every
 * call). Two identical boards (same ids) differ only by that place; if the worker
 * already holds the port at that place, it takes the next one with the same ids it
 * does not hold. Should two identical adapters still swap, nothing goes wrong: the
 * machine knows each board by the name it says in its hello, not by its port.
 */
export interface PortKey {
  usbVendorId: number | null;
  usbProductId: number | null;
  ordinal: number | null;
}

function hex(n: number): string {
  return n.toString(16).padStart(4, '0');
}

export function portLabel(info: Partial<SerialPortInfo>): string {
  if (info.usbVendorId === undefined) return 'serial port';
  return `USB ${hex(info.usbVendorId)}:${hex(info.usbProductId ?? 0)}`;
}

export function keyLabel(key: PortKey): string {
  return portLabel({ usbVendorId: key.usbVendorId ?? undefined, usbProductId: key.usbProductId ?? undefined });
}

function sameIds(port: SerialPortLike, key: PortKey): boolean {
  const info = port.getInfo();
  return (info.usbVendorId ?? null) === key.usbVendorId && (info.usbProductId ?? null) === key.usbProductId;
}

/** The key of `port`, one of `api`'s granted ports. */
export async function portKey(port: SerialPortLike, api: GrantedPorts): Promise<PortKey> {
  const info = port.getInfo();
  const key: PortKey = { usbVendorId: info.usbVendorId ?? null, usbProductId: info.usbProductId ?? null, ordinal: null };
  const index = (await api.getPorts()).filter((p) => sameIds(p, key)).indexOf(port);
  return { ...key, ordinal: index >= 0 ? index : null };
}

/** Why a port named by a key could not be found. */
export class PortNotFound extends Error {}

/**
 * The granted port that `key` names, from this context's own `getPorts()`: the one
 * at its place if this context does not hold it open yet, else the first with the
 * same ids that it does not hold.
 */
export async function findGrantedPort(api: GrantedPorts, key: PortKey): Promise<SerialPortLike> {
  const candidates = (await api.getPorts()).filter((p) => sameIds(p, key));
  const label = keyLabel(key);
  if (candidates.length === 0) {
    throw new PortNotFound(`${label} is granted to the page, but the worker does not see it: it was unplugged just now, or the browser withdrew the permission. Plug it in and press Add device again.`);
  }
  const free = candidates.filter((p) => !isOpen(p));
  const atPlace = key.ordinal !== null ? candidates[key.ordinal] : undefined;
  const port = atPlace && !isOpen(atPlace) ? atPlace : free[0];
  if (!port) throw new PortNotFound(`${label} is connected already (every granted port with these ids is open here).`);
  return port;
}

/** Whether this context has the port open (its streams exist only while it is). */
export function isOpen(port: SerialPortLike): boolean {
  return port.readable !== null && port.writable !== null;
}

export interface OpenedPort {
  label: string;
  readable: ReadableStream<Uint8Array>;
  writable: WritableStream<Uint8Array>;
  /** What reaches the board: its UART at the baud the port runs at (native-USB boards take more). */
  bytesPerSecond: number;
  /** µs a byte on the board's UART, if it has a USB–serial bridge (uartBridges.ts); undefined for native USB. */
  uartByteTime_us: number | undefined;
}

/** Opens a port (if it is not open yet) at the MAXL baud and returns its streams. */
export async function openPort(port: SerialPortLike): Promise<OpenedPort> {
  const label = portLabel(port.getInfo());
  if (!isOpen(port)) await port.open({ baudRate: MAXL_DEFAULT_BAUD });
  const { readable, writable } = port;
  if (!readable || !writable) throw new Error(`${label} opened without streams`);
  return { label, readable, writable, bytesPerSecond: uartBytesPerSecond(MAXL_DEFAULT_BAUD), uartByteTime_us: portUartByteTime_us(port.getInfo()) };
}

/** Words for a failed open (in either context) that a user can act on. */
export function openErrorWords(err: unknown, label: string): string {
  const e = err as { name?: string; message?: string };
  if (err instanceof PortNotFound) return e.message ?? String(err);
  if (e.name === 'InvalidStateError') return `${label} is already open elsewhere (another tab, or the Arduino IDE's serial monitor): close it there and press Add device again.`;
  if (e.name === 'NetworkError') return `${label} could not be opened: ${e.message}. Unplug the board, plug it back in and press Add device again.`;
  if (e.name === 'SecurityError') return `The browser refused access to ${label}: ${e.message}.`;
  return `${label} could not be opened: ${e.message ?? String(err)}`;
}
