/**
 * Machine configurations kept in localStorage, one per simulated machine and one
 * for real boards, plus which machine was open last; and JSON export and import.
 */
import type { MachineConfig } from '../worker/protocol.ts';
import { configShapeProblem } from './configShape.ts';
import { downloadText } from './download.ts';

const KEY = 'maxl.workbench.v1';

/** The key under which real boards' configuration is kept. */
export const BOARDS = 'boards';

interface Stored {
  lastMachine: string | null;
  configs: Record<string, MachineConfig>;
}

function read(): Stored {
  try {
    const raw = localStorage.getItem(KEY);
    if (raw) {
      const parsed = JSON.parse(raw) as Partial<Stored>;
      return { lastMachine: parsed.lastMachine ?? null, configs: parsed.configs ?? {} };
    }
  } catch {
    // unreadable: start afresh
  }
  return { lastMachine: null, configs: {} };
}

function write(s: Stored): void {
  localStorage.setItem(KEY, JSON.stringify(s));
}

export function lastMachine(): string | null {
  return read().lastMachine;
}

export function savedConfig(machine: string): MachineConfig | undefined {
  return read().configs[machine];
}

export function saveConfig(machine: string, config: MachineConfig): void {
  const s = read();
  s.lastMachine = machine;
  s.configs[machine] = config;
  write(s);
}

export function forgetConfig(machine: string): void {
  const s = read();
  delete s.configs[machine];
  write(s);
}

export function exportConfig(config: MachineConfig, name: string): void {
  downloadText(JSON.stringify(config, null, 2), `${name}.maxl.json`, 'application/json');
}

/**
 * Parses an imported file; throws with words a user can act on, importing nothing,
 * when it is not JSON or not a machine configuration the editor can show
 * (configShape.ts). Bad values inside are imported: Configure lists them before Apply.
 */
export function parseConfig(text: string): MachineConfig {
  let value: unknown;
  try {
    value = JSON.parse(text);
  } catch (err) {
    throw new Error(`The file is not JSON: ${(err as Error).message}`);
  }
  if (value === null || typeof value !== 'object' || Array.isArray(value) || !('motionAxes' in value) || !('limits' in value)) {
    throw new Error('The file is not a MAXL machine configuration: it needs at least "motionAxes" and "limits".');
  }
  const shape = configShapeProblem(value as Record<string, unknown>);
  if (shape) throw new Error(`The file is not a MAXL machine configuration: ${shape}. Nothing was imported.`);
  return value as MachineConfig;
}
