/**
 * The few WASI functions a wasm32-wasi build of the firmware may import even
 * though it never runs a WASI program (printf pulls in fd_write, abort pulls
 * in proc_exit). fd_write collects text into the device's console; everything
 * else answers ENOSYS. The firmware has no files, no clock from WASI (its
 * clock is maxl_micros), no arguments.
 */
import { SimError } from '../errors.ts';

export const WASI_MODULE = 'wasi_snapshot_preview1';
const ERRNO_SUCCESS = 0;
const ERRNO_NOSYS = 52;

export function wasiImports(
  name: string,
  memory: () => WebAssembly.Memory,
  writeConsole: (fd: number, text: string) => void,
): (fn: string) => (...args: number[]) => number {
  return (fn) => {
    switch (fn) {
      case 'fd_write':
        return (fd, iovs, iovsLength, writtenPtr) => {
          const view = new DataView(memory().buffer);
          let total = 0;
          let text = '';
          for (let i = 0; i < iovsLength; i++) {
            const ptr = view.getUint32(iovs + 8 * i, true);
            const len = view.getUint32(iovs + 8 * i + 4, true);
            text += new TextDecoder().decode(new Uint8Array(memory().buffer, ptr, len));
            total += len;
          }
          writeConsole(fd, text);
          view.setUint32(writtenPtr, total, true);
          return ERRNO_SUCCESS;
        };
      case 'proc_exit':
        return (code) => {
          throw new SimError('DEVICE_TRAP', `${name}: the firmware called exit(${code})`);
        };
      default:
        return () => ERRNO_NOSYS;
    }
  };
}
