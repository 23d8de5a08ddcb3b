#!/usr/bin/env node
// `npm test`: every test suite, in order. A suite that needs a system tool which
// is missing gets it from scripts/install-system-deps.sh (as root, or with sudo);
// where that cannot run, this stops with the exact command to run. Nothing is
// skipped silently: a suite either runs or the whole run fails.
import { spawnSync } from 'node:child_process';
import { existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import path from 'node:path';
import { suites } from './test-suites.mjs';
import { requireNode } from './require-node.mjs';

requireNode();

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
process.chdir(root);

/** A command on the PATH, or a file (a path; `*` matches one folder name, as in a shell). */
function have(tool) {
  if (tool.includes('*')) return spawnSync('sh', ['-c', `ls ${tool}`], { stdio: 'ignore' }).status === 0;
  if (tool.startsWith('/')) return existsSync(tool);
  return spawnSync('sh', ['-c', `command -v ${tool}`], { stdio: 'ignore' }).status === 0;
}

function ensureTools(tools) {
  const missing = tools.filter((t) => !have(t));
  if (missing.length === 0) return;
  console.log(`[test] missing system tools: ${missing.join(', ')}; installing through scripts/install-system-deps.sh`);
  const isRoot = process.getuid && process.getuid() === 0;
  const cmd = isRoot || !have('sudo') ? ['bash', ['scripts/install-system-deps.sh']] : ['sudo', ['bash', 'scripts/install-system-deps.sh']];
  const r = spawnSync(cmd[0], cmd[1], { stdio: 'inherit' });
  const still = tools.filter((t) => !have(t));
  if (r.status !== 0 || still.length > 0) {
    console.error(`[test] could not install ${still.join(', ') || 'system packages'}. Run, as root:\n  bash scripts/install-system-deps.sh`);
    process.exit(1);
  }
}

const only = process.argv.slice(2);
const chosen = only.length ? suites.filter((s) => only.includes(s.name)) : suites;
if (only.length && chosen.length !== only.length) {
  console.error(`[test] unknown suite in ${only.join(', ')}; suites: ${suites.map((s) => s.name).join(', ')}`);
  process.exit(2);
}
const results = [];
for (const suite of chosen) {
  ensureTools(suite.tools ?? []);
  console.log(`\n[test] === ${suite.name}: ${suite.describe} ===`);
  const started = Date.now();
  const r = spawnSync(suite.command[0], suite.command.slice(1), { stdio: 'inherit', env: { ...process.env, ...(suite.env ?? {}) } });
  const seconds = ((Date.now() - started) / 1000).toFixed(1);
  results.push({ name: suite.name, ok: r.status === 0, seconds });
  if (r.status !== 0) {
    console.error(`[test] ${suite.name} FAILED (exit ${r.status ?? r.signal}) after ${seconds} s`);
    break;
  }
}
console.log('\n[test] summary');
for (const r of results) console.log(`  ${r.ok ? 'pass' : 'FAIL'}  ${r.name}  (${r.seconds} s)`);
const notRun = chosen.slice(results.length).map((s) => s.name);
if (notRun.length) console.log(`  not run after the failure: ${notRun.join(', ')}`);
process.exit(results.every((r) => r.ok) && notRun.length === 0 ? 0 : 1);
