/**
 * The MAXL worker's own way to the serial ports, so that a board's bytes never
 * cross the page's main thread.
 *
 *  - Web Serial: Chrome and Edge expose `navigator.serial` in dedicated workers
 *    (WorkerNavigator.serial), without `requestPort`: the page asks the user for a
 *    port, and the worker finds it among its own `getPorts()` (serialPorts.ts).
 *  - web-serial-polyfill over WebUSB: Chrome exposes `navigator.usb` in dedicated
 *    workers too, and the polyfill uses nothing else a worker lacks (its
 *    `getPorts()` is `navigator.usb.getDevices()`; its streams are plain
 *    ReadableStream/WritableStream). So it runs here as well.
 *
 * A browser whose workers have neither keeps the old bridge: the page opens the
 * port and transfers its streams here ('add-port'), every byte crossing the page,
 * with the wide margins that needs (realBoardStreamer.ts). The page learns which
 * way to go from this worker's `serial-access` answer.
 */
/// <reference lib="webworker" />
/// <reference types="w3c-web-serial" />
/// <reference types="w3c-web-usb" />
import type { GrantedPorts, PortApi, SerialPortLike } from './serialPorts.ts';

export interface SerialAccess {
  /** navigator.serial with getPorts() in this worker */
  serial: boolean;
  /** navigator.usb with getDevices() in this worker, for web-serial-polyfill */
  usb: boolean;
}

type WorkerNav = { serial?: GrantedPorts & Partial<EventTarget>; usb?: { getDevices?: unknown } & Partial<EventTarget> };

function workerNavigator(): WorkerNav {
  return navigator as unknown as WorkerNav;
}

export function serialAccess(): SerialAccess {
  const nav = workerNavigator();
  return { serial: typeof nav.serial?.getPorts === 'function', usb: typeof nav.usb?.getDevices === 'function' };
}

/** This worker's granted ports through `api`. */
export async function grantedPorts(api: PortApi): Promise<GrantedPorts> {
  const nav = workerNavigator();
  if (api === 'serial') {
    if (!nav.serial) throw new Error('this browser has no Web Serial in workers');
    return nav.serial;
  }
  if (!nav.usb) throw new Error('this browser has no WebUSB in workers');
  const polyfill = await import('web-serial-polyfill');
  return polyfill.serial as unknown as GrantedPorts;
}

/**
 * Calls `onGone` when a port disappears (unplugged, or the board reset its USB):
 * Web Serial says which port; WebUSB says which device (vendor and product id).
 */
export function watchDisconnects(onGone: (port: SerialPortLike | null, info: { usbVendorId?: number; usbProductId?: number }) => void): void {
  const nav = workerNavigator();
  nav.serial?.addEventListener?.('disconnect', (e) => {
    const port = e.target as unknown as SerialPortLike | null;
    onGone(port, port?.getInfo?.() ?? {});
  });
  nav.usb?.addEventListener?.('disconnect', (e) => {
    const device = (e as USBConnectionEvent).device;
    onGone(null, { usbVendorId: device?.vendorId, usbProductId: device?.productId });
  });
}
