import { describe, expect, it } from 'vitest';
import { findGrantedPort, portKey, PortNotFound, type SerialPortLike } from './serialPorts.ts';

/** A port as Web Serial has it: open() makes its streams. */
function port(usbVendorId: number, usbProductId: number): SerialPortLike & { opens: number } {
  const p = {
    readable: null as ReadableStream<Uint8Array> | null,
    writable: null as WritableStream<Uint8Array> | null,
    opens: 0,
    async open() {
      p.opens++;
      p.readable = new ReadableStream();
      p.writable = new WritableStream();
    },
    async close() {
      p.readable = null;
      p.writable = null;
    },
    getInfo: () => ({ usbVendorId, usbProductId }),
  };
  return p;
}

const granted = (ports: SerialPortLike[]) => ({ getPorts: async () => ports });

describe('finding a granted port in another context', () => {
  it('tells two identical boards apart by their place among the granted ports', async () => {
    // The page's objects and the worker's are different objects for the same ports, listed in the same order.
    const page = [port(0x2341, 0x43), port(0x2341, 0x42), port(0x2341, 0x43)];
    const worker = [port(0x2341, 0x43), port(0x2341, 0x42), port(0x2341, 0x43)];
    const key = await portKey(page[2], granted(page));
    expect(key).toEqual({ usbVendorId: 0x2341, usbProductId: 0x43, ordinal: 1 });
    expect(await findGrantedPort(granted(worker), key)).toBe(worker[2]);
    expect(await findGrantedPort(granted(worker), await portKey(page[0], granted(page)))).toBe(worker[0]);
  });

  it('takes the next identical port the worker does not hold when the one at that place is open', async () => {
    const worker = [port(0x2341, 0x43), port(0x2341, 0x43)];
    await worker[0].open({ baudRate: 1 });
    expect(await findGrantedPort(granted(worker), { usbVendorId: 0x2341, usbProductId: 0x43, ordinal: 0 })).toBe(worker[1]);
    // The polyfill cannot say the place (new port objects on every call): the first free one.
    expect(await findGrantedPort(granted(worker), { usbVendorId: 0x2341, usbProductId: 0x43, ordinal: null })).toBe(worker[1]);
  });

  it('says so in words when the worker does not see the port, or holds every one with its ids', async () => {
    const worker = [port(0x2341, 0x43)];
    await expect(findGrantedPort(granted(worker), { usbVendorId: 0x1a86, usbProductId: 0x7523, ordinal: 0 })).rejects.toThrow(/USB 1a86:7523 is granted to the page, but the worker does not see it/);
    await worker[0].open({ baudRate: 1 });
    const held = findGrantedPort(granted(worker), { usbVendorId: 0x2341, usbProductId: 0x43, ordinal: 0 });
    await expect(held).rejects.toBeInstanceOf(PortNotFound);
    await expect(held).rejects.toThrow(/is connected already/);
  });
});
