/** The simulated machines, by id. */
import { accelRig } from './accelRig.ts';
import { blotPlotter } from './blotPlotter.ts';
import { cncShield } from './cncShield.ts';
import { lightPainter } from './lightPainter.ts';
import type { MachinePreset } from './presetTypes.ts';

export { accelRig, blotPlotter, cncShield, lightPainter };
export type { MachinePreset, SimulatedDeviceSpec, PresetReader } from './presetTypes.ts';

export const PRESETS: Record<string, () => MachinePreset> = { lightPainter, blotPlotter, accelRig, cncShield };
