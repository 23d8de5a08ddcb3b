/**
 * Node only: loads firmware examples from public/firmware/<Example>.wasm on
 * disk (the browser uses fetchWasmLoader instead; keep this file out of
 * browser imports).
 */
import { readFile } from 'node:fs/promises';
import { fileURLToPath } from 'node:url';
import { cachedLoader, type WasmLoader } from './wasmLoader.ts';

/** The repo's public/firmware directory. */
export const PUBLIC_FIRMWARE_DIR = fileURLToPath(new URL('../../../public/firmware/', import.meta.url));

export function nodeWasmLoader(directory: string = PUBLIC_FIRMWARE_DIR): WasmLoader {
  const dir = directory.endsWith('/') ? directory : `${directory}/`;
  return cachedLoader((example) => readFile(`${dir}${example}.wasm`));
}
