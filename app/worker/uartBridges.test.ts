import { describe, expect, it } from 'vitest';
import { hasUartBridge, portUartByteTime_us } from './uartBridges.ts';

describe('which serial ports reach their board through a UART', () => {
  // [board, its USB ids, whether a UART (40 µs a byte at 250 000 baud) carries its bytes]
  const boards: Array<[string, { usbVendorId?: number; usbProductId?: number }, boolean]> = [
    ['Uno (16U2)', { usbVendorId: 0x2341, usbProductId: 0x0043 }, true],
    ['Mega 2560', { usbVendorId: 0x2341, usbProductId: 0x0042 }, true],
    ['a CH340 clone', { usbVendorId: 0x1a86, usbProductId: 0x7523 }, true],
    ['an FTDI adapter', { usbVendorId: 0x0403, usbProductId: 0x6001 }, true],
    ['a port without USB ids', {}, true],
    ['Leonardo', { usbVendorId: 0x2341, usbProductId: 0x8036 }, false],
    ['Uno R4 Minima', { usbVendorId: 0x2341, usbProductId: 0x0069 }, false],
    ['Teensy', { usbVendorId: 0x16c0, usbProductId: 0x0483 }, false],
    ['Raspberry Pi Pico', { usbVendorId: 0x2e8a, usbProductId: 0x000a }, false],
  ];
  it.each(boards)('%s', (_board, info, uart) => {
    expect(hasUartBridge(info)).toBe(uart);
    expect(portUartByteTime_us(info)).toBe(uart ? 40 : undefined);
  });
});
