#!/usr/bin/env node
// `npm run bench -- NAME`: runs bench/NAME.ts (through tsx) or bench/NAME.mjs.
// Each benchmark prints its figures as one JSON object on the last line of its output.
import { spawnSync } from 'node:child_process';
import { requireNode } from './require-node.mjs';
import { existsSync, readdirSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import path from 'node:path';

requireNode();
const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const name = process.argv[2];
const available = readdirSync(path.join(root, 'bench'))
  .filter((f) => /^[a-z]+\.(ts|mjs)$/.test(f))
  .map((f) => f.replace(/\.(ts|mjs)$/, ''));
if (!name || !available.includes(name)) {
  console.error(`usage: npm run bench -- NAME\n  NAME: ${available.join(', ')}`);
  process.exit(2);
}
const ts = path.join(root, 'bench', `${name}.ts`);
const cmd = existsSync(ts)
  ? ['npx', ['tsx', ts, ...process.argv.slice(3)]]
  : ['node', [path.join(root, 'bench', `${name}.mjs`), ...process.argv.slice(3)]];
const r = spawnSync(cmd[0], cmd[1], { stdio: 'inherit', cwd: root });
process.exit(r.status ?? 1);
