/**
 * Boards over Web Serial, the page's part. "Add device" asks the browser for a
 * port (this needs the user's click, so it runs on the page); the MAXL worker then
 * finds that port among its own granted ports, opens it and owns its streams
 * (app/worker/workerSerial.ts), so that no byte crosses the page. Without
 * navigator.serial but with WebUSB, web-serial-polyfill drives USB CDC boards, in
 * the worker too; with neither, the page says what is needed. Only where the
 * worker cannot reach the ports does the page open them and hand their streams
 * over (the bridge).
 */
/// <reference types="w3c-web-serial" />

import type { SerialApi } from '../worker/serialPorts.ts';

export { openPort, portKey, portLabel, type PortApi, type SerialApi, type SerialPortLike } from '../worker/serialPorts.ts';

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

/** Words for a failed requestPort/open that a user can act on. */
export function connectErrorWords(err: unknown): string {
  const e = err as { name?: string; message?: string };
  if (e.name === 'NotFoundError') return 'No port was chosen.';
  if (e.name === 'SecurityError') return `The browser refused access to serial ports: ${e.message}. ${unsupportedReason()}`;
  if (e.name === 'InvalidStateError') return `The port is already open elsewhere (another tab, or the Arduino IDE's serial monitor): close it there and try again.`;
  if (e.name === 'NetworkError') return `The port could not be opened: ${e.message}. Unplug the board, plug it back in and try again.`;
  return `Could not connect: ${e.message ?? String(err)}`;
}
