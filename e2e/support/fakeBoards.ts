/**
 * Starts and stops the fake boards' Node process (fakeBoardsProcess.ts) for a
 * spec: `startFakeBoards()` in test.beforeAll, `stopFakeBoards()` in
 * test.afterAll. The boards then run outside the browser, as real boards run on
 * hardware of their own, so only the author's side (the page and the MAXL
 * worker) shares the browser's CPU.
 *
 * Their priority: `E2E_BOARDS_NICE` (default -10). A real board has a CPU of its
 * own and competes with nothing on the host; the nearest a process on the same
 * cores comes to that is a higher priority than everything else's (nice < 0,
 * which needs root or CAP_SYS_NICE). With Linux's autogroup scheduling (on by
 * default), nice orders only the processes of one session, and each session
 * competes with the others as a whole: so the process gets a session of its own
 * (`detached`) and that session's autogroup gets the nice value too. Where the
 * system refuses it, the boards run at nice 0, on equal terms with the browser,
 * and `priority` says so.
 */
import { spawn, type ChildProcess } from 'node:child_process';
import { existsSync, writeFileSync } from 'node:fs';
import { setPriority } from 'node:os';
import { fileURLToPath } from 'node:url';

export interface FakeBoards {
  /** ws://127.0.0.1:PORT, where the page's and the worker's fakes reach them. */
  url: string;
  /** The nice value the boards' process runs at, and why if it is not the one asked for. */
  priority: string;
  process: ChildProcess;
}

const ENTRY = fileURLToPath(new URL('./fakeBoardsProcess.ts', import.meta.url));
const STARTUP_MS = 30_000;

/** From the environment: `E2E_BOARDS_NICE` (default -10). */
export function boardsNice(env: NodeJS.ProcessEnv = process.env): number {
  const nice = Number(env.E2E_BOARDS_NICE ?? -10);
  if (!Number.isInteger(nice) || nice < -20 || nice > 19) throw new Error(`E2E_BOARDS_NICE must be a whole number from -20 to 19, not "${env.E2E_BOARDS_NICE}"`);
  return nice;
}

export async function startFakeBoards(nice = boardsNice()): Promise<FakeBoards> {
  // tsx runs the TypeScript (the core's, the fake's) as it is, in Node.
  const child = spawn(process.execPath, ['--import', 'tsx', ENTRY], { stdio: ['pipe', 'pipe', 'inherit'], detached: true });
  const priority = child.pid === undefined ? 'not started' : prioritise(child.pid, nice);
  const url = await new Promise<string>((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`the fake boards did not start within ${STARTUP_MS / 1000} s`)), STARTUP_MS);
    let out = '';
    child.stdout!.setEncoding('utf8');
    child.stdout!.on('data', (text: string) => {
      out += text;
      const found = /listening on (ws:\/\/\S+)/.exec(out);
      if (found) {
        clearTimeout(timer);
        resolve(found[1]);
      }
    });
    child.on('exit', (code, signal) => {
      clearTimeout(timer);
      reject(new Error(`the fake boards' process ended before it listened (exit ${code ?? signal}): ${out}`));
    });
    child.on('error', (err) => reject(new Error(`the fake boards' process could not start: ${err.message}`)));
  });
  // Its later output (a firmware's trap, say) goes to the spec's.
  child.stdout!.on('data', (text: string) => process.stdout.write(`fake boards: ${text}`));
  return { url, priority, process: child };
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

export function stopFakeBoards(boards: FakeBoards | undefined): void {
  if (!boards) return;
  boards.process.stdin?.end();
  if (boards.process.exitCode === null && boards.process.signalCode === null) boards.process.kill('SIGTERM');
}
