/**
 * CPU burners: busy loops in child processes, standing in for a laptop's
 * background work (a compile, a sync, a video call) beside the browser. A spec
 * starts them in test.beforeAll and stops them in test.afterAll.
 *
 * `nice` 10 is the default: background work at a lower priority, as an OS puts
 * it; nice 0 is work at the browser's own priority.
 */
import { spawn, type ChildProcess } from 'node:child_process';

export interface BurnerSettings {
  count: number;
  nice: number;
}

/** From the environment: `E2E_BURNERS` (how many, default 2), `E2E_BURNER_NICE` (default 10; 0 = normal priority). */
export function burnerSettings(env: NodeJS.ProcessEnv = process.env): BurnerSettings {
  const count = Number(env.E2E_BURNERS ?? 2);
  const nice = Number(env.E2E_BURNER_NICE ?? 10);
  if (!Number.isInteger(count) || count < 0) throw new Error(`E2E_BURNERS must be a whole number ≥ 0, not "${env.E2E_BURNERS}"`);
  if (!Number.isInteger(nice) || nice < 0 || nice > 19) throw new Error(`E2E_BURNER_NICE must be a whole number from 0 to 19, not "${env.E2E_BURNER_NICE}"`);
  return { count, nice };
}

export function startCpuBurners({ count, nice }: BurnerSettings): ChildProcess[] {
  const loop = [process.execPath, '-e', 'for (;;) {}'];
  return Array.from({ length: count }, () => {
    const child = nice > 0 ? spawn('nice', ['-n', String(nice), ...loop], { stdio: 'ignore' }) : spawn(loop[0], loop.slice(1), { stdio: 'ignore' });
    child.on('error', (err) => {
      throw new Error(`a CPU burner could not start: ${err.message}`);
    });
    return child;
  });
}

export function stopCpuBurners(burners: ChildProcess[]): void {
  for (const b of burners) if (b.exitCode === null && b.signalCode === null) b.kill('SIGKILL');
}
