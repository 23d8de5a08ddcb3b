/**
 * The import graph of core/ and its layers (docs/architecture.md, "Layers").
 *
 * core/ reads bottom to top, each layer importing only from layers below it or
 * from its own:
 *
 *   base (errors.ts, random.ts) → time → config → plan → trajectory → net →
 *   sim, capture → maxl (maxl.ts, runtime.ts, index.ts) → system
 *
 * Every import counts, `import type` and `export … from` too: a reader follows a
 * type-only import the same way. Test files (*.test.ts, *.hil.ts) and the test
 * support in core/testing/ sit above every layer: they may import any of them,
 * and nothing but tests may import them.
 *
 * `coreImportProblems()` lists every upward import and every cycle (between
 * files, and between the folders that make a layer); core/layers.test.ts fails on
 * any of them, and `npx tsx scripts/coreLayers.ts` prints them.
 */
import { readdirSync, readFileSync, statSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import ts from 'typescript';

/** Layers, lowest first: a file's layer is that of the first rule matching its path (relative to core/, '/' separated). */
export const CORE_LAYERS: ReadonlyArray<{ name: string; match: (file: string) => boolean }> = [
  { name: 'base', match: (f) => f === 'errors.ts' || f === 'random.ts' },
  { name: 'time', match: (f) => f.startsWith('time/') },
  { name: 'config', match: (f) => f.startsWith('config/') },
  { name: 'plan', match: (f) => f.startsWith('plan/') },
  { name: 'trajectory', match: (f) => f.startsWith('trajectory/') },
  { name: 'net', match: (f) => f.startsWith('net/') },
  { name: 'sim/capture', match: (f) => f.startsWith('sim/') || f.startsWith('capture/') },
  { name: 'maxl', match: (f) => f === 'maxl.ts' || f === 'runtime.ts' || f === 'index.ts' },
  { name: 'system', match: (f) => f.startsWith('system/') },
];

/** Tests and their support: above every layer. */
export function isTestFile(file: string): boolean {
  return file.startsWith('testing/') || file.endsWith('.test.ts') || file.endsWith('.hil.ts');
}

export function layerOf(file: string): number {
  if (isTestFile(file)) return CORE_LAYERS.length;
  const i = CORE_LAYERS.findIndex((l) => l.match(file));
  return i;
}

function layerName(i: number): string {
  return i === CORE_LAYERS.length ? 'tests' : (CORE_LAYERS[i]?.name ?? 'no layer');
}

const here = path.dirname(fileURLToPath(import.meta.url));
export const CORE_DIR = path.resolve(here, '..', 'core');

function listTs(dir: string, out: string[] = []): string[] {
  for (const name of readdirSync(dir)) {
    const full = path.join(dir, name);
    if (statSync(full).isDirectory()) listTs(full, out);
    else if (name.endsWith('.ts') && !name.endsWith('.d.ts')) out.push(full);
  }
  return out;
}

/** Every core file (relative, '/'-separated) → the core files it imports (type-only, re-exports and dynamic imports included). */
export function coreImportGraph(coreDir = CORE_DIR): Map<string, string[]> {
  const graph = new Map<string, string[]>();
  const rel = (full: string) => path.relative(coreDir, full).split(path.sep).join('/');
  for (const file of listTs(coreDir)) {
    const info = ts.preProcessFile(readFileSync(file, 'utf8'), true, true);
    const targets: string[] = [];
    for (const ref of info.importedFiles) {
      if (!ref.fileName.startsWith('.')) continue; // packages and node: builtins
      const target = path.resolve(path.dirname(file), ref.fileName);
      if (!target.startsWith(coreDir + path.sep)) continue; // outside core/ (none should be; see below)
      targets.push(rel(target));
    }
    graph.set(rel(file), targets);
  }
  return graph;
}

/** Strongly connected components with more than one node (or a self-loop): Tarjan's algorithm. */
export function cycles(graph: ReadonlyMap<string, readonly string[]>): string[][] {
  let index = 0;
  const indexOf = new Map<string, number>();
  const low = new Map<string, number>();
  const stack: string[] = [];
  const onStack = new Set<string>();
  const found: string[][] = [];
  const visit = (v: string) => {
    indexOf.set(v, index);
    low.set(v, index);
    index++;
    stack.push(v);
    onStack.add(v);
    for (const w of graph.get(v) ?? []) {
      if (!indexOf.has(w)) {
        visit(w);
        low.set(v, Math.min(low.get(v)!, low.get(w)!));
      } else if (onStack.has(w)) low.set(v, Math.min(low.get(v)!, indexOf.get(w)!));
    }
    if (low.get(v) === indexOf.get(v)) {
      const component: string[] = [];
      let w: string;
      do {
        w = stack.pop()!;
        onStack.delete(w);
        component.push(w);
      } while (w !== v);
      if (component.length > 1 || (graph.get(v) ?? []).includes(v)) found.push(component.sort());
    }
  };
  for (const v of graph.keys()) if (!indexOf.has(v)) visit(v);
  return found;
}

/** The folder a file is in ('.' for core/ itself): the unit of the folder-level cycle check. */
function folderOf(file: string): string {
  const slash = file.indexOf('/');
  return slash < 0 ? '.' : file.slice(0, slash);
}

/**
 * Every breach, in words: a file in no layer, an import out of core/ (to app/,
 * say), an import from a higher layer, a non-test file importing a test file, a
 * cycle of files, a cycle of folders.
 */
export function coreImportProblems(coreDir = CORE_DIR): string[] {
  const graph = coreImportGraph(coreDir);
  const problems: string[] = [];
  for (const [file, targets] of graph) {
    const from = layerOf(file);
    if (from < 0) {
      problems.push(`${file} is in no layer: add it to CORE_LAYERS in scripts/coreLayers.ts`);
      continue;
    }
    for (const target of targets) {
      if (!graph.has(target)) continue; // a missing file: the typecheck says so
      const to = layerOf(target);
      if (to > from) problems.push(`${file} (${layerName(from)}) imports ${target} (${layerName(to)}), a higher layer`);
    }
  }
  // Test files may read shared fixtures (scripts/protocol-vectors.ts); the core itself imports nothing outside core/.
  for (const file of listTs(coreDir)) {
    if (isTestFile(path.relative(coreDir, file).split(path.sep).join('/'))) continue;
    const info = ts.preProcessFile(readFileSync(file, 'utf8'), true, true);
    for (const ref of info.importedFiles) {
      if (!ref.fileName.startsWith('.')) continue;
      const target = path.resolve(path.dirname(file), ref.fileName);
      if (!target.startsWith(coreDir + path.sep)) problems.push(`${path.relative(coreDir, file)} imports ${ref.fileName}, outside core/`);
    }
  }
  for (const c of cycles(graph)) problems.push(`import cycle between files: ${c.join(' ⇄ ')}`);
  // Folders: a cycle of folders is a cycle of a layer's parts, even when no file cycle exists.
  // core/ itself holds the base (errors.ts, random.ts) and the maxl layer: it is two folders for this check.
  const splitRoot = new Map<string, string[]>();
  for (const [file, targets] of graph) {
    if (isTestFile(file)) continue;
    const name = (f: string) => (folderOf(f) === '.' ? `./${layerName(layerOf(f))}` : folderOf(f));
    const from = name(file);
    const list = splitRoot.get(from) ?? [];
    for (const t of targets) {
      const to = name(t);
      if (to !== from && !list.includes(to)) list.push(to);
    }
    splitRoot.set(from, list);
  }
  for (const c of cycles(splitRoot)) problems.push(`import cycle between folders: ${c.join(' ⇄ ')}`);
  return problems;
}

if (process.argv[1] && path.resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const problems = coreImportProblems();
  for (const p of problems) console.log(p);
  console.log(problems.length === 0 ? 'core/: no upward import, no cycle' : `core/: ${problems.length} problem(s)`);
  process.exit(problems.length === 0 ? 0 : 1);
}
