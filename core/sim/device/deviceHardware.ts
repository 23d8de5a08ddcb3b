/**
 * What a simulated board's pins and buses are connected to: the side effects
 * of the wasm ABI's imports (firmware/src/maxl/hal/wasm_imports.h), each with
 * the author time at which the firmware did it. The plant implements this for
 * each device it wires up; `t_us` never goes backwards across calls for one
 * machine (the device runner steps every device in time order).
 */
export interface DeviceHardware {
  /** Mode 0 input, 1 output, 2 input with pull-up. */
  pinMode(pin: number, mode: number, t_us: number): void;
  digitalWrite(pin: number, value: number, t_us: number): void;
  digitalRead(pin: number, t_us: number): number;
  /** PWM duty 0..255. */
  analogWrite(pin: number, value: number, t_us: number): void;
  /** An RGB strip on `pin` shows 3 bytes per LED. */
  ledShow(pin: number, rgb: Uint8Array, t_us: number): void;
  /** Returns an Arduino Wire status: 0 ACK, 2 address NACK, 3 data NACK. */
  i2cWrite(address: number, data: Uint8Array, t_us: number): number;
  /** The bytes read, or null if no device answers at `address`. */
  i2cRead(address: number, length: number, t_us: number): Uint8Array | null;
  /** A hobby-servo pulse width, µs; 0 detaches. */
  servoPulse(pin: number, pulse_us: number, t_us: number): void;
}

/** Hardware with nothing attached: inputs read low, I2C gets no answer. */
export const UNCONNECTED: DeviceHardware = {
  pinMode: () => {},
  digitalWrite: () => {},
  digitalRead: () => 0,
  analogWrite: () => {},
  ledShow: () => {},
  i2cWrite: () => 2,
  i2cRead: () => null,
  servoPulse: () => {},
};
