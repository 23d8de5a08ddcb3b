#!/usr/bin/env node
// `npm run bench -- fuzz [--runs N] [--jobs J] [--seed S] [--max-seconds T]`: the firmware's
// libFuzzer target (firmware/fuzz/fuzz_device.cpp: the frame receiver, the
// session, every message handler, the motion state machine and the readers,
// on the host hardware layer, under ASan and UBSan) run at scale: N executions
// in all (default 10 000 000), split over J fuzzer processes (default 2, the
// machine's cores), each from the seed corpus firmware/fuzz/corpus plus the
// shared working corpus firmware/build/fuzz/corpus. `npm test` keeps its short
// 25 s run (scripts/firmware-fuzz.sh). With --max-seconds T each process also
// stops after T seconds (libFuzzer's -max_total_time), and the JSON says how far
// it got; SIGINT stops the processes the same way (libFuzzer prints its stats).
// Both exit non-zero when fewer than N executions ran.
//
// Prints one JSON object as the last line. Every figure is parsed from
// libFuzzer's own output (-print_final_stats=1), never assumed:
//
//   executions     sum over the processes of stat::number_of_executed_units
//                  (the inputs libFuzzer actually ran, corpus replay included)
//   crashes        inputs that made a process stop: a sanitizer report, a
//                  deadly signal, an invariant abort(), a leak, a timeout
//                  (> 5 s) or out of memory; each leaves its input in
//                  firmware/build/fuzz/bench-<kind>-<sha1> (listed in `artifacts`)
//   seconds        wall time of the fuzzing, the longest process's own
//                  "Done N runs in S second(s)" summed over its restarts
//   execPerSecond  executions / seconds
//   perProcess     each process's executions, seconds and libFuzzer's
//                  stat::average_exec_per_sec
//   coverage       the highest "cov:" (edges reached) any process printed
// A process that crashes is restarted for the rest of its share (at most 3
// crashes each), so one crash does not hide the next.
import { spawn, spawnSync } from 'node:child_process';
import { createWriteStream, mkdirSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { positiveIntArg } from './args.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const out = path.join(root, 'firmware', 'build', 'fuzz');
const totalRuns = positiveIntArg('--runs', 10_000_000);
const jobs = positiveIntArg('--jobs', 2);
const baseSeed = positiveIntArg('--seed', 1 + (Date.now() % 1_000_000));
const maxSeconds = positiveIntArg('--max-seconds', 0);
const deadline = maxSeconds > 0 ? Date.now() + maxSeconds * 1000 : Infinity;
let interrupted = false;
const live = new Set();
process.on('SIGINT', () => {
  interrupted = true; // each fuzzer, told the same, prints its stats and stops
  for (const p of live) p.kill('SIGINT');
});
const MAX_CRASHES_PER_PROCESS = 3;
const log = (...a) => console.error('[bench fuzz]', ...a);

// ---- build (clang, -fsanitize=fuzzer,address,undefined; the same flags as npm test's run)
log('building firmware/build/fuzz/fuzz_device');
const build = spawnSync('bash', ['scripts/firmware-fuzz.sh', '--build'], { cwd: root, stdio: 'inherit' });
if (build.status !== 0) {
  log('the build failed');
  process.exit(1);
}
mkdirSync(path.join(out, 'corpus'), { recursive: true });

/** One libFuzzer process for `runs` executions; resolves to what its output said. */
function fuzzOnce(worker, attempt, runs) {
  const logFile = path.join(out, `bench-${baseSeed}-${worker}-${attempt}.log`);
  const sink = createWriteStream(logFile);
  const args = [
    path.join(out, 'corpus'),
    path.join(root, 'firmware', 'fuzz', 'corpus'),
    `-runs=${runs}`,
    `-seed=${baseSeed + 1000 * worker + attempt}`,
    '-max_len=4096',
    '-timeout=5',
    '-print_final_stats=1',
    `-artifact_prefix=${out}/bench-`,
    ...(deadline === Infinity ? [] : [`-max_total_time=${Math.max(1, Math.round((deadline - Date.now()) / 1000))}`]),
  ];
  return new Promise((resolve, reject) => {
    const p = spawn(path.join(out, 'fuzz_device'), args, { cwd: root, stdio: ['ignore', 'pipe', 'pipe'] });
    live.add(p);
    const result = { executions: null, seconds: null, execPerSecond: null, coverage: 0, artifact: null, status: null, tail: '', stoppedEarly: false };
    let pending = '';
    let lastProgress = 0;
    const onText = (chunk) => {
      sink.write(chunk);
      pending += chunk.toString();
      const lines = pending.split('\n');
      pending = lines.pop();
      for (const line of lines) {
        result.tail = (result.tail + line + '\n').slice(-4000);
        let m;
        if ((m = line.match(/^#(\d+)\s+\S+\s+cov: (\d+)/))) {
          result.coverage = Math.max(result.coverage, Number(m[2]));
          if (Date.now() - lastProgress > 30_000) {
            lastProgress = Date.now();
            log(`process ${worker}: ${Number(m[1]).toLocaleString('en')} of ${runs.toLocaleString('en')} runs, cov ${m[2]}`);
          }
        }
        if ((m = line.match(/^Done (\d+) runs in (\d+) second/))) result.seconds = Number(m[2]);
        if ((m = line.match(/^stat::number_of_executed_units:\s+(\d+)/))) result.executions = Number(m[1]);
        if ((m = line.match(/^stat::average_exec_per_sec:\s+(\d+)/))) result.execPerSecond = Number(m[1]);
        if ((m = line.match(/Test unit written to (\S+)/))) result.artifact = m[1];
        if (/libFuzzer: run interrupted; exiting/.test(line)) result.stoppedEarly = true;
      }
    };
    p.stdout.on('data', onText);
    p.stderr.on('data', onText);
    p.on('error', reject);
    p.on('close', (status) => {
      live.delete(p);
      sink.end();
      result.status = status;
      result.logFile = path.relative(root, logFile);
      resolve(result);
    });
  });
}

/** A worker's share, restarted after a crash for what is left of it. */
async function worker(index, share) {
  const acc = { executions: 0, seconds: 0, execPerSecond: [], coverage: 0, crashes: [], logs: [], stoppedEarly: false };
  let attempt = 0;
  while (acc.executions < share && acc.crashes.length < MAX_CRASHES_PER_PROCESS) {
    const started = Date.now();
    const r = await fuzzOnce(index, attempt++, share - acc.executions);
    acc.logs.push(r.logFile);
    if (r.executions === null) {
      throw new Error(`process ${index}: libFuzzer printed no stat::number_of_executed_units (exit ${r.status}); ${r.logFile}:\n${r.tail}`);
    }
    acc.executions += r.executions;
    // "Done N runs in S second(s)" only ends a clean run; after a crash, the
    // process's life (measured here) stands in for it, and says so.
    acc.seconds += r.seconds ?? (Date.now() - started) / 1000;
    if (r.execPerSecond !== null) acc.execPerSecond.push(r.execPerSecond);
    acc.coverage = Math.max(acc.coverage, r.coverage);
    if (r.stoppedEarly || interrupted || Date.now() >= deadline - 5000) {
      acc.stoppedEarly = true; // SIGINT or --max-seconds: not a crash
      break;
    }
    if (r.status !== 0 || r.artifact) {
      acc.crashes.push({ artifact: r.artifact ? path.relative(root, r.artifact) : null, log: r.logFile, exit: r.status });
      log(`process ${index}: CRASH (exit ${r.status}), input ${r.artifact ?? '(none written)'}; see ${r.logFile}`);
      if (r.executions === 0) break; // it cannot even start: do not loop
    }
  }
  return acc;
}

const wallStart = Date.now();
log(`${totalRuns.toLocaleString('en')} executions over ${jobs} processes, seeds from ${baseSeed}`);
const shares = Array.from({ length: jobs }, (_, i) => Math.floor(totalRuns / jobs) + (i < totalRuns % jobs ? 1 : 0));
const results = await Promise.all(shares.map((share, i) => worker(i, share)));
const executions = results.reduce((s, r) => s + r.executions, 0);
const seconds = Math.max(...results.map((r) => r.seconds));
const crashes = results.flatMap((r) => r.crashes);
const summary = {
  executions,
  crashes: crashes.length,
  seconds,
  execPerSecond: Math.round(executions / Math.max(seconds, 1)),
  wallSeconds: Math.round((Date.now() - wallStart) / 1000),
  processes: jobs,
  seed: baseSeed,
  coverage: Math.max(...results.map((r) => r.coverage)),
  perProcess: results.map((r) => ({ executions: r.executions, seconds: r.seconds, averageExecPerSec: r.execPerSecond })),
  artifacts: crashes.map((c) => c.artifact ?? c.log),
  requestedExecutions: totalRuns,
  stoppedEarly: results.some((r) => r.stoppedEarly) ? (interrupted ? 'SIGINT' : `--max-seconds ${maxSeconds}`) : null,
};
console.log(JSON.stringify(summary));
process.exit(crashes.length > 0 || executions < totalRuns ? 1 : 0);
