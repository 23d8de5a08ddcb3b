/**
 * Starts and stops the fake boards' Node process (fakeBoardsProcess.ts) for a
 * spec: `startFakeBoards()` in test.beforeAll, `stopFakeBoards()` in
 * test.afterAll. The boards then run outside the browser, as real boards run on
 * hardware of their own, so only the author's side (the page and the MAXL
 * worker) shares the browser's CPU.
 *
 * Their priority, `E2E_BOARDS_PRIORITY`:
 *  - `realtime` (the default): the process goes under SCHED_FIFO once it listens
 *    (`chrt --all-tasks --pid`, which needs root or CAP_SYS_NICE), so it runs the
 *    moment a timer or a socket wakes it, ahead of every ordinary process: the nearest a process on the same cores
 *    comes to a board's CPU of its own. It needs ~12 % of one core (three devices'
 *    firmware every 100 µs of simulated time), so it takes little from the
 *    others, and Linux keeps 5 % of each core for them whatever it does
 *    (sched_rt_runtime_us). Measured on the shared 2-core machine under load: a
 *    1 ms timer came at most 3.5 ms late under SCHED_FIFO in 10 s, against 55 ms
 *    at nice -10 in an autogroup of its own and 111 ms at nice 0.
 *  - `nice`: nice -10, in a session (so an autogroup) of its own at nice -10: with
 *    Linux's autogroup scheduling (on by default), nice orders only the processes
 *    of one session, and each session competes with the others as a whole.
 *  - `equal`: nice 0, in the spec's session: on equal terms with the browser.
 * Where the system refuses what was asked, the process runs at the next one down
 * and `priority` says so.
 */
import { spawn, spawnSync, type ChildProcess } from 'node:child_process';
import { existsSync, writeFileSync } from 'node:fs';
import { setPriority } from 'node:os';
import { fileURLToPath } from 'node:url';

export interface FakeBoards {
  /** ws://127.0.0.1:PORT, where the page's and the worker's fakes reach them. */
  url: string;
  /** How the boards' process is scheduled, and why if it is not what was asked for. */
  priority: string;
  process: ChildProcess;
}

export type BoardsPriority = 'realtime' | 'nice' | 'equal';

const ENTRY = fileURLToPath(new URL('./fakeBoardsProcess.ts', import.meta.url));
const STARTUP_MS = 30_000;
/** SCHED_FIFO priority (1–99): above every ordinary process, below the kernel's own threads (50). */
const FIFO_PRIORITY = 10;
const NICE = -10;

/** From the environment: `E2E_BOARDS_PRIORITY` (default realtime). */
export function boardsPriority(env: NodeJS.ProcessEnv = process.env): BoardsPriority {
  const p = env.E2E_BOARDS_PRIORITY ?? 'realtime';
  if (p !== 'realtime' && p !== 'nice' && p !== 'equal') throw new Error(`E2E_BOARDS_PRIORITY must be realtime, nice or equal, not "${p}"`);
  return p;
}

export async function startFakeBoards(asked = boardsPriority()): Promise<FakeBoards> {
  // tsx runs the TypeScript (the core's, the fake's) as it is, in Node. The process starts at
  // normal priority in a session (so an autogroup) of its own unless asked to be `equal`, and is
  // raised once it listens (see promote()).
  const ownSession = asked !== 'equal';
  const child = spawn(process.execPath, ['--import', 'tsx', ENTRY], { stdio: ['pipe', 'pipe', 'inherit'], detached: ownSession });
  const url = await listeningUrl(child).catch((err: Error) => {
    // Not left running (and at whatever priority) after a failed start.
    child.kill('SIGKILL');
    throw err;
  });
  const priority = child.pid === undefined ? 'nice 0 (no pid to raise)' : promote(child.pid, asked);
  // Its later output (a firmware's trap, say) goes to the spec's.
  child.stdout!.on('data', (text: string) => process.stdout.write(`fake boards: ${text}`));
  return { url, priority, process: child };
}

/**
 * Raises the listening boards' process as asked, and says what it got. Under
 * `realtime` its threads go to SCHED_FIFO only once it listens, its start-up
 * (tsx compiling the TypeScript through esbuild, a process of its own that stays
 * ordinary; V8 compiling the firmware) done at normal priority: a process started
 * under SCHED_FIFO livelocked there on a busy core (`taskset -c 0 chrt --fifo 10
 * node --import tsx fakeBoardsProcess.ts` on a clean clone never listened in
 * 120 s, two of its threads spinning at 95 % each; raised afterwards, it listens
 * in ~1 s), which is how CI saw "the fake boards did not start within 30 s".
 * All its threads, not only the main one: with V8's helper threads left ordinary,
 * the main thread waited on them (a garbage collection) and single wakes of the
 * boards ran 12–49 ms (worstRun_ms, 5 runs under load ~7), against under 1.5 ms
 * with every thread raised.
 */
function promote(pid: number, asked: BoardsPriority): string {
  if (asked === 'equal') return 'nice 0, on equal terms with the browser';
  if (asked === 'realtime') {
    const fifo = spawnSync('chrt', ['--all-tasks', '--fifo', '--pid', String(FIFO_PRIORITY), String(pid)], { encoding: 'utf8' });
    if (!fifo.error && fifo.status === 0) return `SCHED_FIFO ${FIFO_PRIORITY}`;
    const why = fifo.error ? `chrt: ${fifo.error.message}` : fifo.stderr.trim() || `chrt exited ${fifo.status}`;
    return `SCHED_FIFO was refused (${why}): ${prioritise(pid, NICE)}`;
  }
  return prioritise(pid, NICE);
}

export function stopFakeBoards(boards: FakeBoards | undefined): void {
  if (!boards) return;
  boards.process.stdin?.end();
  if (boards.process.exitCode === null && boards.process.signalCode === null) boards.process.kill('SIGTERM');
}

/** Gives process `pid` (a session leader) nice `nice`, and its autogroup too where there is one; says what it got. */
function prioritise(pid: number, nice: number): string {
  try {
    setPriority(pid, nice);
  } catch (err) {
    return `nice 0 (nice ${nice} was refused: ${(err as Error).message}; the boards compete with the browser on equal terms)`;
  }
  const autogroup = `/proc/${pid}/autogroup`;
  if (!existsSync(autogroup)) return `nice ${nice}`;
  try {
    writeFileSync(autogroup, String(nice));
    return `nice ${nice}, in an autogroup of its own at nice ${nice}`;
  } catch (err) {
    return `nice ${nice}, in an autogroup of its own at nice 0 (nice ${nice} was refused: ${(err as Error).message})`;
  }
}

/** The server's address, from the process's first line of output. */
function listeningUrl(child: ChildProcess): Promise<string> {
  return new Promise<string>((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`the fake boards did not start within ${STARTUP_MS / 1000} s; they printed: ${JSON.stringify(out)}`)), STARTUP_MS);
    let out = '';
    child.stdout!.setEncoding('utf8');
    const onData = (text: string) => {
      out += text;
      const found = /listening on (ws:\/\/\S+)/.exec(out);
      if (!found) return;
      clearTimeout(timer);
      child.stdout!.off('data', onData);
      resolve(found[1]);
    };
    child.stdout!.on('data', onData);
    child.on('exit', (code, signal) => {
      clearTimeout(timer);
      reject(new Error(`the fake boards' process ended before it listened (exit ${code ?? signal}): ${out}`));
    });
    child.on('error', (err) => reject(new Error(`the fake boards' process could not start: ${err.message}`)));
  });
}
