/**
 * Where firmware .wasm files come from. The simulator asks for an example by
 * name ("Stepper") and gets a compiled module. In the browser the files are
 * served from /firmware/<Example>.wasm (vite's public/); in Node,
 * nodeWasmLoader.ts reads public/firmware/ from disk. Tests may inject their
 * own loader.
 */
import { SimError } from '../errors.ts';

export type WasmLoader = (example: string) => Promise<WebAssembly.Module>;

/** Compiles each example once, however many devices run it. */
export function cachedLoader(load: (example: string) => Promise<BufferSource>): WasmLoader {
  const cache = new Map<string, Promise<WebAssembly.Module>>();
  return (example) => {
    let module = cache.get(example);
    if (!module) {
      module = load(example).then(
        (bytes) => WebAssembly.compile(bytes),
        (err: unknown) => {
          throw new SimError('WASM_LOAD_FAILED', `firmware example "${example}" could not be loaded: ${String(err)}`, { cause: err });
        },
      );
      cache.set(example, module);
    }
    return module;
  };
}

/** Fetches `${baseUrl}${example}.wasm` (default: /firmware/, where vite serves public/firmware). */
export function fetchWasmLoader(baseUrl = '/firmware/'): WasmLoader {
  return cachedLoader(async (example) => {
    const url = `${baseUrl}${example}.wasm`;
    const response = await fetch(url);
    if (!response.ok) throw new Error(`GET ${url}: ${response.status} ${response.statusText}`);
    return response.arrayBuffer();
  });
}
