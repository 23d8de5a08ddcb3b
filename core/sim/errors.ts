/**
 * Errors the simulator raises. Like MaxlError, each has a stable `code` to
 * branch on and a message a user can act on.
 */
export type SimErrorCode =
  | 'WASM_LOAD_FAILED' // the firmware .wasm could not be read or fetched
  | 'WASM_ABI' // the module lacks an export the ABI requires, or imports something unknown
  | 'DEVICE_TRAP' // the firmware trapped (out of bounds, unreachable...) while running
  | 'SIM_CONFIG' // a preset or option is inconsistent
  | 'LINK_CLOSED'; // bytes written to a link after close()

export class SimError extends Error {
  readonly code: SimErrorCode;
  constructor(code: SimErrorCode, message: string, options?: { cause?: unknown }) {
    super(message, options);
    this.name = 'SimError';
    this.code = code;
  }
}
