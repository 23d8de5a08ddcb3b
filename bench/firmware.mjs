#!/usr/bin/env node
// `npm run bench -- firmware`: performance of the reader library on an
// ATmega328P (simulated cycle by cycle by simavr) and on the host. Prints one
// JSON object as the last line:
//
//   avrCyclesPerEval      CPU cycles of one position evaluation (the hot path
//                         of MAXL_Device::loop(), Motion::tick for one slot),
//                         mean over a 100 mm move evaluated every 20 µs;
//                         Timer 1 at clk/1 around each call (EvalCycles sketch)
//   avrCyclesPerEvalSpiral, …SpiralP99, …SpiralMax
//                         the same for two slots along 300 mm of a spiral in
//                         0.5 mm pieces (firmware/bench/bench_spiral.h): a
//                         segment ends every 3.3 ms at 150 mm/s, phases of
//                         1–3 µs where rounding makes them; mean, 99th
//                         percentile (upper edge of its 8-cycle bin) and largest
//   avrCyclesPerEvalMax   the largest evaluation of all the runs above
//   avrStepRateHz         the highest cruise step rate R such that at EVERY
//                         rate on the 250 Hz grid from avrStepRateSweptFromHz
//                         up to R one stepper (the Stepper example's device,
//                         fed real frames over the simulated UART) emits every
//                         step within one step period after its ideal time,
//                         none more than 2 µs early, none missing (libsimavr
//                         harness, see bench/firmware/simavr_steps.c). Found
//                         in two passes: a binary search on the grid
//                         (…SearchHz: clean there, but the misses do not always
//                         grow with the rate, so rates below it may miss), then
//                         an ascending sweep of every grid rate from half the
//                         search's rate (…SweptFromHz) that stops at the first
//                         miss (…FirstMissHz, null if none up to …SearchHz).
//                         The same four fields for each step-rate figure below.
//   avrStepRateTwoSteppersHz  the same for two steppers on the timer at once
//                         (BlotPlotter's CoreXY pair), each at the rate
//                         (StepRate and StepRateTwo are built with the Stepper
//                         and BlotPlotter examples' build_flags.txt: firmware/README.md)
//   avrStepRateTwoSteppers30DegHz  the same pair on a CoreXY line at 30° to x:
//                         motor a at the rate, motor b at 0.268 of it, each
//                         checked against its own step period
//   avrStepRateThreeSteppersHz  three steppers (StepRateThree: the CncShield
//                         example's x, y, z and its build_flags.txt), each at
//                         the rate, every step of all three checked (6 segments:
//                         its queue holds 6)
//   examples              { Name: { flashFree, ramFree } }: bytes of the Uno's
//                         32 256 of flash and 2 048 of static RAM (.data + .bss)
//                         each firmware example leaves free
//   hostInstructionsPerEval  the same evaluation on the host (callgrind)
//   bytesPerLinearSegment merged from bench/segment-bytes.ts (the TS encoder)
//                         when that file exists
// Measured every run; nothing is hard-coded.
//
// Options (after `npm run bench -- firmware`; or `node bench/firmware.mjs …`):
//   --only LIST           measure only these parts, comma-separated, of
//                         eval (the evaluation cycles), one, two, two30, three
//                         (the step-rate searches), examples (flash and RAM),
//                         host (callgrind), segment (bytesPerLinearSegment);
//                         the JSON then holds only their fields. Default: all.
//   --from HZ --to HZ     bracket each step-rate search: HZ of --from is tried
//                         first and, if it passes, is the lower end (else the
//                         upper); --to's is tried and, if it fails, is the
//                         upper end (else 80 000 is); then halving as always
//                         (defaults 0 and 80 000). Fewer trials near a known
//                         figure; the figure can differ from the default
//                         search's only where misses do not grow with the
//                         rate (a pass above a fail). The sweep then starts at
//                         half the search's rate as always.
// Wall time of `--only one,two,two30,three` (the searches and sweeps, ~200
// simavr runs): 2–3.5 minutes on the 2-core machine at load ~5 (firmware/README.md).
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, readdirSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const out = path.join(root, 'firmware', 'build', 'bench');
mkdirSync(out, { recursive: true });

function run(cmd, args, options = {}) {
  const r = spawnSync(cmd, args, { cwd: root, encoding: 'utf8', maxBuffer: 64 << 20, ...options });
  if (r.error) throw new Error(`${cmd}: ${r.error.message}`);
  return r;
}
function must(cmd, args, what) {
  const r = run(cmd, args);
  if (r.status !== 0) {
    process.stderr.write(r.stdout + r.stderr);
    throw new Error(`${what} failed (${cmd} exit ${r.status})`);
  }
  return r.stdout + r.stderr;
}
const PARTS = ['eval', 'one', 'two', 'two30', 'three', 'examples', 'host', 'segment'];
function option(name) {
  const i = process.argv.indexOf(name);
  if (i < 0) return undefined;
  const value = process.argv[i + 1];
  if (value === undefined || value.startsWith('--')) throw new Error(`${name} needs a value`);
  return value;
}
const onlyList = option('--only');
const only = new Set(onlyList ? onlyList.split(',').map((p) => p.trim()) : PARTS);
for (const p of only) if (!PARTS.includes(p)) throw new Error(`--only: unknown part "${p}" (known: ${PARTS.join(', ')})`);
function hzOption(name, fallback) {
  const text = option(name);
  const hz = Number(text ?? fallback);
  if (!Number.isInteger(hz) || hz < 0 || hz > 80000) throw new Error(`${name}: expected a whole number of Hz from 0 to 80 000, got "${text}"`);
  return hz;
}
const fromHz = hzOption('--from', 0);
const toHz = hzOption('--to', 80000);
if (fromHz >= toHz) throw new Error(`--from ${fromHz} must be below --to ${toHz}`);
const want = (part) => only.has(part);
const log = (...a) => console.log('[bench firmware]', ...a);
const clean = (s) => s.replace(/\x1b\[[0-9;]*m/g, '');

// ---- builds
const sketches = [
  ['EvalCycles', want('eval')],
  ['StepRate', want('one')],
  ['StepRateTwo', want('two') || want('two30')],
  ['StepRateThree', want('three')],
];
for (const [sketch, needed] of sketches) {
  if (!needed) continue;
  must('bash', ['scripts/firmware-avr-sketch.sh', `firmware/bench/${sketch}`, out], `AVR build of ${sketch}`);
}
const harness = path.join(out, 'simavr_steps');
must('gcc', ['-O2', '-Wall', '-o', harness, 'bench/firmware/simavr_steps.c', '-lsimavr', '-lm'], 'the simavr harness build');

// ---- cycles per evaluation
let one, two, spiral;
if (want('eval')) {
const evalOut = clean(must('timeout', ['600', 'simavr', '-m', 'atmega328p', '-f', '16000000', path.join(out, 'EvalCycles/EvalCycles.elf')], 'EvalCycles in simavr'));
if (/FAIL/.test(evalOut)) throw new Error(`EvalCycles failed:\n${evalOut}`);
const parse = (label) => {
  const m = evalOut.match(new RegExp(`RESULT ${label} evaluations=(\\d+) meanCycles=([\\d.]+) p99Cycles=(\\d+) maxCycles=(\\d+)`));
  if (!m) throw new Error(`no "${label}" result from EvalCycles:\n${evalOut}`);
  return { evaluations: Number(m[1]), mean: Number(m[2]), p99: Number(m[3]), max: Number(m[4]) };
};
one = parse('oneSlot');
two = parse('twoSlots');
spiral = parse('spiral');
log(`evaluation, one slot: ${one.mean} cycles mean, ${one.max} max over ${one.evaluations}; two slots: ${two.mean} mean, ${two.max} max`);
log(`evaluation, spiral of 0.5 mm pieces (two slots): ${spiral.mean} mean, p99 ${spiral.p99}, max ${spiral.max} over ${spiral.evaluations}`);
}

// ---- step rate: binary search for the highest rate without a missed step,
// for one stepper (the Stepper example) and for two (BlotPlotter's CoreXY pair,
// both stepping at the rate: STEPPERS=2 in the harness)
function searchRate(label, elf, env) {
  const trials = new Map();
  function trial(rate) {
    if (trials.has(rate)) return trials.get(rate);
    const r = run('timeout', ['600', harness, elf, String(rate)], { env: { ...process.env, ...env } });
    const line = (r.stdout || '').trim().split('\n').pop();
    let result;
    try {
      result = JSON.parse(line);
    } catch {
      throw new Error(`harness gave no JSON at ${rate} Hz (${label}):\n${r.stdout}${r.stderr}`);
    }
    if (result.nacks || result.steps === 0) throw new Error(`the device refused the move at ${rate} Hz (${label}): ${line}`);
    log(`${label}, ${rate} Hz: ${result.missed} missed of ${result.expected} (late ${result.late}, early ${result.early}), max lag ${result.maxLagUs} µs, loop ${result.loopMeanCycles} cycles mean, ${(result.loopMaxCycles / 16).toFixed(0)} µs max`);
    trials.set(rate, result);
    return result;
  }
  const STEP = 250;
  let lo = 0;
  let hi = 80000;
  if (fromHz > 0) {
    if (trial(fromHz).missed === 0) lo = fromHz;
    else hi = fromHz;
  }
  if (toHz < hi && trial(toHz).missed > 0) hi = toHz;
  if (hi === 80000 && trial(hi).missed === 0) lo = hi;
  while (hi - lo > STEP) {
    const mid = Math.round((lo + hi) / 2 / STEP) * STEP;
    if (mid <= lo || mid >= hi) break;
    if (trial(mid).missed === 0) lo = mid;
    else hi = mid;
  }
  log(lo ? `${label}: the search's highest rate without a missed step: ${lo} Hz` : `${label}: steps were missed at every rate tried`);
  // The misses do not always grow with the rate (a pass can sit above a fail),
  // so the search's rate alone is not "every rate below is clean". Sweep the
  // grid upward from half the search's rate (trials already run are reused)
  // and stop at the first miss: the figure is the last clean rate before it.
  const floor = Math.max(STEP, Math.round((lo * SWEEP_FLOOR) / STEP) * STEP);
  let clean = 0;
  let firstMiss = null;
  for (let rate = floor; lo && rate <= lo; rate += STEP) {
    if (trial(rate).missed > 0) {
      firstMiss = rate;
      break;
    }
    clean = rate;
  }
  if (lo) log(`${label}: every rate from ${floor} Hz clean up to ${clean} Hz${firstMiss ? `, first miss at ${firstMiss} Hz` : ''}`);
  return { rate: clean, searched: lo, floor: lo ? floor : null, firstMiss, best: clean ? trials.get(clean) : null };
}
// where the sweep starts, as a fraction of the search's rate
const SWEEP_FLOOR = 0.5;
// the JSON fields of one step-rate figure: the swept figure and what stands beside it
function rateFields(name, r, definition) {
  return {
    [`${name}Hz`]: r.rate,
    [`${name}SearchHz`]: r.searched,
    [`${name}SweptFromHz`]: r.floor,
    [`${name}FirstMissHz`]: r.firstMiss,
    [`${name}Definition`]: definition,
  };
}
const single = want('one') ? searchRate('one stepper', path.join(out, 'StepRate/StepRate.elf'), {}) : null;
const pair = want('two') ? searchRate('two steppers', path.join(out, 'StepRateTwo/StepRateTwo.elf'), { STEPPERS: '2' }) : null;
const pair30 = want('two30') ? searchRate('two steppers at 30°', path.join(out, 'StepRateTwo/StepRateTwo.elf'), { STEPPERS: '2', ANGLE_DEG: '30' }) : null;
const three = want('three') ? searchRate('three steppers', path.join(out, 'StepRateThree/StepRateThree.elf'), { STEPPERS: '3', CRUISE_SEGMENTS: '4' }) : null;

// ---- flash and RAM each example leaves free on the Uno (its build_flags.txt)
function exampleSizes() {
  const FLASH = 32256; // 32 KiB minus the 512-byte bootloader
  const RAM = 2048;
  const sizes = {};
  const examplesOut = path.join(out, 'examples');
  for (const name of readdirSync(path.join(root, 'firmware/examples')).sort()) {
    must('bash', ['scripts/firmware-avr-sketch.sh', `firmware/examples/${name}`, examplesOut], `AVR build of ${name}`);
    const line = must('avr-size', [path.join(examplesOut, name, `${name}.elf`)], `avr-size of ${name}`).trim().split('\n').pop();
    const [text, data, bss] = line.trim().split(/\s+/).map(Number);
    sizes[name] = { flashFree: FLASH - (text + data), ramFree: RAM - (data + bss) };
    log(`${name}: ${sizes[name].flashFree} bytes of flash and ${sizes[name].ramFree} of RAM free`);
  }
  return sizes;
}
const examples = want('examples') ? exampleSizes() : undefined;

// ---- host instructions per evaluation (callgrind)
let hostInstructionsPerEval;
if (want('host')) {
const hostBin = path.join(out, 'eval_host');
const library = readdirSync(path.join(root, 'firmware/src'), { recursive: true })
  .filter((f) => f.endsWith('.cpp'))
  .map((f) => path.join('firmware/src', f))
  .sort();
must('g++', ['-std=c++11', '-O2', '-fno-exceptions', '-fno-rtti', '-Ifirmware/src', 'bench/firmware/eval_host.cpp', ...library, '-o', hostBin], 'the host evaluation build');
if (run('sh', ['-c', 'command -v valgrind']).status === 0) {
  const instructions = (n) => {
    const r = run('valgrind', ['--tool=callgrind', '--callgrind-out-file=/dev/null', hostBin, String(n)]);
    const m = (r.stderr || '').match(/Collected : (\d+)/);
    if (!m) throw new Error(`callgrind gave no count:\n${r.stderr}`);
    return Number(m[1]);
  };
  const n1 = 10000;
  const n2 = 210000;
  hostInstructionsPerEval = Number(((instructions(n2) - instructions(n1)) / (n2 - n1)).toFixed(1));
  log(`host: ${hostInstructionsPerEval} instructions per evaluation (callgrind, g++ -O2)`);
} else {
  process.stderr.write('[bench firmware] valgrind not found: hostInstructionsPerEval omitted\n');
}
}

// ---- bytes per linear segment, from the TS encoder
let bytesPerLinearSegment;
if (!want('segment')) {
  // not asked for (--only)
} else if (existsSync(path.join(root, 'bench/segment-bytes.ts'))) {
  const r = run('npx', ['tsx', 'bench/segment-bytes.ts']);
  const last = (r.stdout || '').trim().split('\n').pop();
  try {
    const j = JSON.parse(last);
    bytesPerLinearSegment = j.bytesPerLinearSegment;
    log(`bytesPerLinearSegment from bench/segment-bytes.ts: ${bytesPerLinearSegment}`);
  } catch {
    process.stderr.write(`[bench firmware] bench/segment-bytes.ts printed no JSON last line (exit ${r.status}): bytesPerLinearSegment omitted\n`);
  }
} else {
  process.stderr.write('[bench firmware] bench/segment-bytes.ts does not exist yet: bytesPerLinearSegment omitted\n');
}

const best = single?.best;
const result = {
  ...(one
    ? {
        avrCyclesPerEval: one.mean,
        avrCyclesPerEvalMax: Math.max(one.max, two.max, spiral.max),
        avrCyclesPerEvalTwoSlots: two.mean,
        avrCyclesPerEvalSpiral: spiral.mean,
        avrCyclesPerEvalSpiralP99: spiral.p99,
        avrCyclesPerEvalSpiralMax: spiral.max,
        avrCyclesPerEvalDefinition:
          'Motion::tick cycles (Timer 1 at clk/1, interrupts off), one evaluation every 20 µs: a 100 mm move (one and two slots) and 300 mm of a spiral in 0.5 mm pieces (two slots); Max is the largest of all',
      }
    : {}),
  ...(single
    ? {
        ...rateFields('avrStepRate', single,
          'highest cruise rate R (250 Hz grid, 80 steps/mm, 10000 mm/s² ramps, 300 ms cruise, all frames sent before the move, STATUS reports running) such that at EVERY grid rate from SweptFromHz (half the search\'s rate) up to R every step edge comes within one step period after its ideal time, none more than 2 µs early, none missing; SearchHz is the binary search\'s clean rate (rates below it may miss), FirstMissHz the sweep\'s first missing rate (null: none up to SearchHz)'),
      }
    : {}),
  ...(best ? { avrStepRateMaxLagUs: best.maxLagUs, avrLoopCyclesMean: best.loopMeanCycles, avrLoopMaxUs: Number((best.loopMaxCycles / 16).toFixed(1)) } : {}),
  ...(pair
    ? {
        ...rateFields('avrStepRateTwoSteppers', pair, 'the same move on two steppers at once (StepRateTwo: STEP D2 and D3, both on the step timer, as BlotPlotter), each at the rate; every step of both checked; figure, SearchHz, SweptFromHz and FirstMissHz as avrStepRate\'s'),
      }
    : {}),
  ...(pair30
    ? {
        ...rateFields('avrStepRateTwoSteppers30Deg', pair30, 'the same pair on a CoreXY line at 30° to x: motor a (x + y) at the rate, motor b (x − y) at 0.268 of it; every step of both checked against its own period; figure, SearchHz, SweptFromHz and FirstMissHz as avrStepRate\'s'),
      }
    : {}),
  ...(three
    ? {
        ...rateFields('avrStepRateThreeSteppers', three, 'the same move on three steppers (StepRateThree: the CncShield example, STEP D2, D3, D4, 6 segments), each at the rate; every step of all three checked; figure, SearchHz, SweptFromHz and FirstMissHz as avrStepRate\'s'),
      }
    : {}),
  ...(examples ? { examples } : {}),
  ...(hostInstructionsPerEval !== undefined ? { hostInstructionsPerEval } : {}),
  ...(bytesPerLinearSegment !== undefined ? { bytesPerLinearSegment } : {}),
};
console.log(JSON.stringify(result));
