/**
 * The simulated machine (docs/design.md, decision 8): real firmware examples in
 * wasm behind simulated USB links, driving a plant. No DOM and no Node
 * imports here, so it runs in Node, a Worker or a page; in Node, import the
 * disk loader from './device/nodeWasmLoader.ts'.
 */
export { createSimulatedMachine, type SimulatedMachine, type SimulatedMachineOptions } from './machine.ts';
export { PRESETS, lightPainter, blotPlotter, accelRig, cncShield, type MachinePreset, type SimulatedDeviceSpec, type PresetReader } from './presets/index.ts';
export { fetchWasmLoader, cachedLoader, type WasmLoader } from './device/wasmLoader.ts';
export { SimulatedLink, type DevicePort, type LinkReport } from './link/simulatedLink.ts';
export { USB_FULL_SPEED_LINK, UNO_UART_LINK, resolveLinkConfig, type LinkConfig, type LinkDirectionConfig, type LinkOverrides } from './link/linkConfig.ts';
export type { LinkDirectionCounters } from './link/linkCounters.ts';
export { WasmDevice, type WasmDeviceOptions, type OutputRecord, type DeviceCounters } from './device/wasmDevice.ts';
export { DeviceRunner } from './device/deviceRunner.ts';
export { DeviceClock, type DeviceClockConfig } from './device/deviceClock.ts';
export type { DeviceHardware } from './device/deviceHardware.ts';
export { Plant } from './plant/plant.ts';
export type { PlantConfig } from './plant/plantConfig.ts';
export type { ToolAxisState } from './plant/springAxis.ts';
export type { PenStroke, PenTransition } from './plant/penServo.ts';
export { SimError, type SimErrorCode } from './errors.ts';
export { seededRandom, gaussian, deriveSeed } from '../random.ts';
