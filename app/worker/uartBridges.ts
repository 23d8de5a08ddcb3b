/**
 * Whether a board behind a USB serial port takes its bytes through a UART: a
 * USB–serial bridge chip (an Uno's 16U2, a CH340, an FTDI, a CP210x) passes them on
 * at the baud rate, 10 bits a byte, while a native-USB board (Leonardo, Teensy,
 * RP2040, an ESP32-S3's own USB) takes them straight from USB at any rate. Clock sync
 * counts the PING's and PONG's bytes on such a UART (core/net/clockSync.ts, "Frames
 * take time on a UART"), so a port says which it is by its USB ids.
 *
 * The ids known to be native USB are listed; every other port, and one without USB
 * ids, is taken for a bridge: the Uno, the reference board, and every clone with a
 * CH340 or an FTDI. A native board not listed here would get a sync error of
 * (16 − 10 bytes) × 40 µs / 2 = 120 µs (its segments would start that much late).
 */
import { MAXL_DEFAULT_BAUD, uartByteTime_us } from '../../core/net/link.ts';

/** USB vendors whose boards' serial ports are the processor's own USB. */
const NATIVE_USB_VENDORS = new Set([
  0x16c0, // PJRC Teensy
  0x2e8a, // Raspberry Pi RP2040 / RP2350
  0x303a, // Espressif's own USB (ESP32-S2/S3/C3 USB-Serial/JTAG)
  0x239a, // Adafruit (SAMD, nRF52, RP2040 boards)
]);

/** Arduino's (0x2341, and 0x2a03 of arduino.org) native-USB products; their other boards (Uno, Mega, Nano Every) have a bridge. */
const ARDUINO_VENDORS = new Set([0x2341, 0x2a03]);
const ARDUINO_NATIVE_PRODUCTS = new Set([
  0x0036, 0x8036, // Leonardo (bootloader, sketch)
  0x0037, 0x8037, // Micro
  0x003e, // Due, native port
  0x004d, 0x804d, // Zero, native port
  0x804e, 0x8050, 0x8052, 0x8053, 0x8054, 0x8055, // MKR boards
  0x0069, // Uno R4 Minima
]);

export function hasUartBridge(info: { usbVendorId?: number; usbProductId?: number }): boolean {
  const vendor = info.usbVendorId;
  if (vendor === undefined) return true;
  if (NATIVE_USB_VENDORS.has(vendor)) return false;
  if (ARDUINO_VENDORS.has(vendor) && info.usbProductId !== undefined && ARDUINO_NATIVE_PRODUCTS.has(info.usbProductId)) return false;
  return true;
}

/** The link's UART byte time for a port with these ids, opened at the MAXL baud (undefined: native USB). */
export function portUartByteTime_us(info: { usbVendorId?: number; usbProductId?: number }): number | undefined {
  return hasUartBridge(info) ? uartByteTime_us(MAXL_DEFAULT_BAUD) : undefined;
}
