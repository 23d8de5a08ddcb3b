/**
 * core/ has no import cycle and no upward import (scripts/coreLayers.ts, docs/architecture.md "Layers").
 * The checker itself is tried on a small tree with one of each breach, so that it can fail.
 */
import { mkdtempSync, mkdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { coreImportProblems, cycles } from '../scripts/coreLayers.ts';

describe('the layers of core/', () => {
  it('has no import cycle and no import from a higher layer (type-only imports count)', () => {
    expect(coreImportProblems()).toEqual([]);
  });

  describe('the checker', () => {
    const root = mkdtempSync(path.join(tmpdir(), 'core-layers-'));
    afterAll(() => rmSync(root, { recursive: true, force: true }));
    const write = (file: string, text: string) => {
      mkdirSync(path.dirname(path.join(root, file)), { recursive: true });
      writeFileSync(path.join(root, file), text);
    };
    write('errors.ts', 'export const e = 1;\n');
    write('plan/a.ts', "import type { S } from '../trajectory/s.ts';\nexport type A = S;\n");
    write('trajectory/s.ts', "export type S = number;\n");
    write('trajectory/m.ts', "import { n } from './n.ts';\nexport const m = n;\n");
    write('trajectory/n.ts', "export { m as n } from './m.ts';\n");
    write('net/x.ts', "import { y } from '../sim/y.ts';\nexport const x = y;\n");
    write('sim/y.ts', "import '../../app/page.ts';\nexport const y = 1;\n");
    write('misc/z.ts', 'export const z = 1;\n');
    write('net/x.test.ts', "import { y } from '../sim/y.ts';\nimport '../../scripts/fixture.ts';\nexport const t = y;\n");

    const problems = coreImportProblems(root);

    it('finds a type-only import from a higher layer', () => {
      expect(problems).toContain('plan/a.ts (plan) imports trajectory/s.ts (trajectory), a higher layer');
      expect(problems).toContain('net/x.ts (net) imports sim/y.ts (sim/capture), a higher layer');
    });
    it('finds a cycle of files, re-exports included', () => {
      expect(problems).toContain('import cycle between files: trajectory/m.ts ⇄ trajectory/n.ts');
    });
    it('finds an import out of core/ and a file in no layer', () => {
      expect(problems).toContain('sim/y.ts imports ../../app/page.ts, outside core/');
      expect(problems.some((p) => p.startsWith('misc/z.ts is in no layer'))).toBe(true);
    });
    it('lets tests import any layer, and fixtures outside core/', () => {
      expect(problems.filter((p) => p.startsWith('net/x.test.ts'))).toEqual([]);
    });
    it('finds cycles of several nodes', () => {
      const graph = new Map([
        ['a', ['b']],
        ['b', ['c']],
        ['c', ['a']],
        ['d', ['a']],
      ]);
      expect(cycles(graph)).toEqual([['a', 'b', 'c']]);
    });
  });
});
