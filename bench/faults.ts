/**
 * npm run bench -- faults
 *
 * The whole fault matrix (issue 11 §2), real firmware in wasm, virtual time, seeded:
 *   - cut: the link of a randomly chosen board cut at FAULTS_CUTS (default 100) random
 *     moments of the job, on each of the three presets;
 *   - corrupt1e-3: every byte of every link corrupted with probability 10⁻³, both ways;
 *     planDiff_mm compares the executed plan with a clean run's (0 = identical);
 *   - corrupt1e-2: the same at 10⁻²: completes, or stops on the path and resumes;
 *   - latency: both directions of one board's link 200 ms slower for 200 ms;
 *   - reboot: one board restarts mid-job (fresh firmware, micros() from 0);
 *   - clockJump / clockJumpBack: one board's µs counter jumps 50 ms ahead / 20 ms back
 *     mid-job (the firmware's check mends its clock and stops taking timing);
 *   - wrap: the link cut just after the board's u32 µs counter wrapped;
 *   - longJob: FAULTS_HOURS (default 8) hours, a stroke every 5 minutes, a 150 ppm crystal.
 * Each case stops (except corruption that resends through), undoes the fault,
 * reconnect()s and resumeJob()s to the job's end. Per kind and preset the JSON gives:
 *   cases, survived (every check below passed),
 *   worstDetection_ms / medianDetection_ms: fault → the author's stop record,
 *   worstOffPathAtRest_mm: carriage from the path once at rest (beyond the boards' spread),
 *   worstOffPath_mm: carriage from the path over the whole run (beyond the spread),
 *   worstBack_mm: worst step back along the path (beyond the spread; > 0.03 = path run twice),
 *   worstLateSteps: worst excess over the plan while followed (> 0 = late or partial segment),
 *   worstEndError_mm: carriage from the job's end at the end,
 *   restSteady / stateOk / resumed: how many cases had motors still at rest, the right
 *   stop reason and "Streaming stopped" words, and ran to the job's end;
 *   endedBeforeStop: cases whose job had run to its end before the stop (a cut in its
 *   last moments, detected by the 300 ms silence limit after the end): for them the
 *   words must say the job "had already run to its end" and reconnect() find nothing left.
 * Survival limits: detection < 500 ms, off the path ≤ 0.03 mm (0.5 mm after a restart,
 * whose position is estimated), back ≤ 0.03 mm, late ≤ 0 steps (not checked after a
 * restart), end ≤ 0.02 mm (0.5 mm after a restart).
 *
 * A part of the matrix alone (each unset: all of it, as above):
 *   FAULTS_PRESETS=blotPlotter,accelRig   the presets' rows to run;
 *   FAULTS_KINDS=corrupt1e-2,clockJump     the rows' cases to run, by their names in the JSON
 *                                          (cut, corrupt1e-3, corrupt1e-2, latency, reboot,
 *                                          clockJump, wrap, clockJumpBack, longJob);
 *   FAULTS_CORRUPT_SEEDS=78 or 1-30,78     the seeds of the corrupt1e-2 cases (default 78),
 *                                          one case each, summarised together.
 * e.g. seed 78's corruption case on the Blot alone:
 *   FAULTS_PRESETS=blotPlotter FAULTS_KINDS=corrupt1e-2 npm run bench -- faults
 */
import { seededRandom } from '../core/random.ts';
import { PRESETS, runFaultCase, type FaultCase, type FaultKind, type FaultOutcome, type PresetName } from '../core/system/faultCases.ts';
import { runLongJob } from '../core/system/longJob.ts';
import { seedListEnv } from './args.mjs';

const CUTS = Number(process.env.FAULTS_CUTS ?? 100);
const HOURS = Number(process.env.FAULTS_HOURS ?? 8);
const ALL_PRESETS: PresetName[] = ['blotPlotter', 'lightPainter', 'accelRig'];
const ALL_KINDS = ['cut', 'corrupt1e-3', 'corrupt1e-2', 'latency', 'reboot', 'clockJump', 'wrap', 'clockJumpBack', 'longJob'];
/** A comma-separated list from `name`, each item one of `allowed`; all of them when unset (exit 2 on an unknown one). */
function listEnv<T extends string>(name: string, allowed: readonly T[]): T[] {
  const spec = process.env[name];
  if (spec === undefined || spec === '') return [...allowed];
  const items = spec.split(',').map((s) => s.trim());
  const unknown = items.filter((s) => !allowed.includes(s as T));
  if (unknown.length > 0) {
    console.error(`${name}: ${unknown.map((u) => `"${u}"`).join(', ')} not known; choose from ${allowed.join(', ')}`);
    process.exit(2);
  }
  return items as T[];
}
const presets = listEnv('FAULTS_PRESETS', ALL_PRESETS);
const kinds = new Set(listEnv('FAULTS_KINDS', ALL_KINDS));
const corruptSeeds = seedListEnv('FAULTS_CORRUPT_SEEDS', [78]);

function survived(r: FaultOutcome, mustStop: boolean): boolean {
  const restarted = r.case.kind === 'reboot';
  const tolerance = restarted ? 0.5 : 0.03;
  return (
    (!mustStop || r.stops > 0) &&
    (r.stops === 0 || (r.detection_ms !== null && r.detection_ms < 500)) &&
    r.restSteady &&
    r.offPathAtRest_mm <= 0.03 + r.spread_mm &&
    r.offPath_mm <= tolerance + r.spread_mm &&
    r.worstBack_mm <= 0.03 &&
    (restarted || r.lateSteps <= 0) &&
    r.stateOk &&
    r.resumed &&
    r.endError_mm <= (restarted ? 0.5 : 0.02)
  );
}

function summarise(rs: FaultOutcome[], mustStop: boolean) {
  const det = rs.map((r) => r.detection_ms).filter((d): d is number => d !== null).sort((a, b) => a - b);
  const worst = (f: (r: FaultOutcome) => number) => Math.max(...rs.map(f));
  return {
    cases: rs.length,
    survived: rs.filter((r) => survived(r, mustStop)).length,
    stops: rs.reduce((n, r) => n + r.stops, 0),
    reasons: [...new Set(rs.flatMap((r) => r.reasons))],
    worstDetection_ms: det.length ? det[det.length - 1] : null,
    medianDetection_ms: det.length ? det[Math.floor(det.length / 2)] : null,
    worstOffPathAtRest_mm: worst((r) => r.offPathAtRest_mm - r.spread_mm),
    worstOffPath_mm: worst((r) => r.offPath_mm - r.spread_mm),
    worstSpread_mm: worst((r) => r.spread_mm),
    worstBack_mm: worst((r) => r.worstBack_mm),
    worstLateSteps: worst((r) => r.lateSteps),
    worstEndError_mm: worst((r) => r.endError_mm),
    restSteady: rs.filter((r) => r.restSteady).length,
    stateOk: rs.filter((r) => r.stateOk).length,
    resumed: rs.filter((r) => r.resumed).length,
    endedBeforeStop: rs.filter((r) => r.endedBeforeStop).length,
    resends: rs.reduce((n, r) => n + r.resends, 0),
    failed: rs.filter((r) => !survived(r, mustStop)).map((r) => ({ ...r, plan: undefined })),
  };
}

const started = Date.now();
const matrix: Record<string, Record<string, unknown>> = {};
const random = seededRandom(20261124);
const log = (what: string) => console.log(`${((Date.now() - started) / 1000).toFixed(0)} s  ${what}`);

for (const preset of presets) {
  const devices = PRESETS[preset]().devices.map((d) => d.name);
  const firstMotor = PRESETS[preset]().plant.motors[0].device;
  const row: Record<string, unknown> = {};
  // The cuts: a random board, a random moment (drawn even when not run, so each cut
  // is the same case whatever runs beside it).
  const cuts: FaultOutcome[] = [];
  for (let k = 0; k < CUTS; k++) {
    const c: FaultCase = { preset, kind: 'cut', seed: 1000 + k, at: 0.05 + 0.9 * random(), device: devices[Math.floor(random() * devices.length)] };
    if (!kinds.has('cut')) continue;
    cuts.push(await runFaultCase(c));
    if ((k + 1) % 10 === 0) log(`${preset}: ${k + 1} cuts`);
  }
  if (kinds.has('cut')) row.cut = summarise(cuts, true);
  // Corruption: 1e-3 against a clean run, and 1e-2.
  if (kinds.has('corrupt1e-3')) {
    const clean = await runFaultCase({ preset, kind: 'corrupt', seed: 77, at: 0, corruption: 0 });
    const low = await runFaultCase({ preset, kind: 'corrupt', seed: 77, at: 0, corruption: 1e-3 });
    let planDiff = low.plan.length === clean.plan.length ? 0 : Infinity;
    clean.plan.forEach((p, k) => p.forEach((v, i) => (planDiff = Math.max(planDiff, Math.abs((low.plan[k]?.[i] ?? Infinity) - v)))));
    row['corrupt1e-3'] = { ...summarise([low], false), planDiff_mm: planDiff, identical: low.stops === 0 && planDiff < 1e-6 };
  }
  if (kinds.has('corrupt1e-2')) {
    const runs: FaultOutcome[] = [];
    for (const seed of corruptSeeds) runs.push(await runFaultCase({ preset, kind: 'corrupt', seed, at: 0, corruption: 1e-2 }));
    row['corrupt1e-2'] = { ...summarise(runs, false), seeds: corruptSeeds };
  }
  for (const kind of ['latency', 'reboot', 'clockJump', 'wrap'] as FaultKind[]) {
    if (kinds.has(kind)) row[kind] = summarise([await runFaultCase({ preset, kind, seed: 79, at: 0.45, device: firstMotor })], true);
  }
  if (kinds.has('clockJumpBack')) row.clockJumpBack = summarise([await runFaultCase({ preset, kind: 'clockJump', seed: 80, at: 0.55, device: firstMotor, jump_us: -20_000 })], true);
  matrix[preset] = row;
  log(`${preset} done`);
}

// The matrix so far, in case the long job is cut short (the last line below has everything).
console.log(JSON.stringify({ matrixBeforeLongJob: matrix }));
if (kinds.has('longJob')) log(`long job: ${HOURS} h`);
const longJob = kinds.has('longJob') ? await runLongJob(HOURS * 3.6e9, 300_000_000) : null;
const cases = Object.values(matrix).flatMap((row) => Object.values(row) as Array<{ cases: number; survived: number }>);
console.log(
  JSON.stringify({
    cutsPerPreset: kinds.has('cut') ? CUTS : 0,
    totalCases: cases.reduce((n, c) => n + c.cases, 0),
    totalSurvived: cases.reduce((n, c) => n + c.survived, 0),
    matrix,
    longJob: longJob && { ...longJob, bounded: longJob.worstLateSteps <= 0 && longJob.errors.length === 0 },
    wallSeconds: (Date.now() - started) / 1000,
  }),
);
