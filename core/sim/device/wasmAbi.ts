/**
 * The simulator's side of the firmware's wasm ABI: what a firmware .wasm
 * imports (module "env", firmware/src/maxl/hal/wasm_imports.h) and what it
 * must export (firmware/WASM_ABI.md). Names live here and nowhere else.
 */
import { SimError } from '../errors.ts';

export const IMPORT_MODULE = 'env';

export const ImportName = {
  micros: 'maxl_micros',
  serialWrite: 'maxl_serial_write',
  pinMode: 'maxl_pin_mode',
  digitalWrite: 'maxl_digital_write',
  digitalRead: 'maxl_digital_read',
  analogWrite: 'maxl_analog_write',
  ledShow: 'maxl_led_show',
  i2cWrite: 'maxl_i2c_write',
  i2cRead: 'maxl_i2c_read',
  servoPulse: 'maxl_servo_pulse',
} as const;

/**
 * Exports, each with the names accepted for it, first match wins. Static
 * constructors (readers link themselves into a list) run from the reactor
 * initialiser before setup.
 */
export const ExportNames = {
  memory: ['memory'],
  initialise: ['_initialize', '__wasm_call_ctors'],
  setup: ['maxl_setup', 'setup'],
  loop: ['maxl_loop', 'loop'],
  /** Returns non-zero when nothing is due before new input (MAXL_Device::idle()). */
  idle: ['maxl_idle', 'maxl_is_idle'],
  rxBuffer: ['maxl_rx_buffer'],
  rxPush: ['maxl_rx_push'],
  /** Optional: µs until the firmware next has something to do (0 now, 0xFFFFFFFF nothing), to sleep a device until then. */
  wakeAfter: ['maxl_wake_after'],
  /** Optional: bytes still in the receive ring. Without it the host estimates (see WasmDevice). */
  rxPending: ['maxl_rx_pending', 'maxl_rx_available'],
} as const;

/** Size of the buffer maxl_rx_buffer() points at (hal_wasm.cpp RX_STAGING). */
export const RX_STAGING_BYTES = 256;

export interface FirmwareExports {
  memory: WebAssembly.Memory;
  initialise: (() => void) | null;
  setup: () => void;
  loop: () => void;
  idle: (() => number) | null;
  wakeAfter: (() => number) | null;
  rxBuffer: () => number;
  rxPush: (length: number) => number;
  rxPending: (() => number) | null;
}

export function resolveExports(instance: WebAssembly.Instance, label: string): FirmwareExports {
  const ex = instance.exports as Record<string, unknown>;
  const find = (names: readonly string[]) => names.map((n) => ex[n]).find((v) => v !== undefined);
  const required = <T>(key: keyof typeof ExportNames): T => {
    const v = find(ExportNames[key]);
    if (v === undefined) {
      throw new SimError(
        'WASM_ABI',
        `${label}: the firmware exports none of ${ExportNames[key].join(', ')} (it exports: ${Object.keys(ex).join(', ')}); is it built for the simulator (firmware/WASM_ABI.md)?`,
      );
    }
    return v as T;
  };
  return {
    memory: required<WebAssembly.Memory>('memory'),
    initialise: (find(ExportNames.initialise) as (() => void) | undefined) ?? null,
    setup: required<() => void>('setup'),
    loop: required<() => void>('loop'),
    idle: (find(ExportNames.idle) as (() => number) | undefined) ?? null,
    wakeAfter: (find(ExportNames.wakeAfter) as (() => number) | undefined) ?? null,
    rxBuffer: required<() => number>('rxBuffer'),
    rxPush: required<(n: number) => number>('rxPush'),
    rxPending: (find(ExportNames.rxPending) as (() => number) | undefined) ?? null,
  };
}
