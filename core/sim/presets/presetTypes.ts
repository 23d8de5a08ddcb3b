/**
 * A simulated machine, described once: the MAXL config an app would write
 * for it, the devices (each a firmware example running in wasm) and the
 * plant they drive. Device and reader names are exactly those the firmware
 * examples report in HELLO and READER, so the config's subscriptions work
 * unchanged on the simulator and on real boards running the same examples.
 */
import type { MaxlConfig } from '../../config/types.ts';
import type { DeviceClockConfig } from '../device/deviceClock.ts';
import type { LinkOverrides } from '../link/linkConfig.ts';
import type { PlantConfig } from '../plant/plantConfig.ts';

/** A reader as the firmware declares it (protocol §4, READER; kind codes per "Reader kinds"). */
export interface PresetReader {
  name: string;
  kind: 'position' | 'velocity' | 'acceleration' | 'event' | 'sensor';
}

export interface SimulatedDeviceSpec {
  /** The device's name as its firmware reports it in HELLO; also the key of its link. */
  name: string;
  /** Firmware example: firmware/examples/<example>, built to public/firmware/<example>.wasm. */
  example: string;
  /**
   * The device name compiled into the example, when this device runs it
   * under another name (two boards flashed with the same Stepper sketch, its
   * `MAXL_Device maxl("motorOne")` line edited to "motorA" and "motorB").
   */
  firmwareName?: string;
  /** The readers the example declares, in its READER order. */
  readers: PresetReader[];
  /** The board's crystal: offset at author time 0 and drift. */
  clock: DeviceClockConfig;
  /** Link shaping for this device (defaults: USB full speed, no faults). */
  link?: LinkOverrides;
  /** Loop period while busy, µs (default 20). */
  loopPeriod_us?: number;
  /** Loop period while idle, µs (default 20 000). */
  idleTick_us?: number;
}

export interface MachinePreset {
  /** Short id: "lightPainter", "blotPlotter", "accelRig", "cncShield". */
  id: string;
  description: string;
  config: MaxlConfig;
  devices: SimulatedDeviceSpec[];
  plant: PlantConfig;
}
