/**
 * The dev/test-only hook into the MAXL worker (docs/test-hooks.md): a test puts
 * `window.__MAXL_WORKER_TEST_HOOK__ = { module, port }` on the page before the
 * workbench starts (Playwright's addInitScript), and the worker imports `module`
 * and calls its `installInWorker(port)` before it handles any command. The
 * WebSerial spec installs its fake `navigator.serial` in the worker this way: an
 * init script reaches only the page, and a port object cannot be sent to a worker.
 *
 * Only a dev server has it: both ends sit behind `import.meta.env.DEV`, which
 * `vite build` replaces with false and then drops (workerClient.ts, maxlWorker.ts).
 */

/** What the page hands the worker, as its first message. */
export interface WorkerTestHook {
  type: 'worker-test-hook';
  /** A module URL the dev server serves (e.g. `/@fs/…/e2e/support/x.ts`). */
  module: string;
  /** A channel for the module (to a fake's other end, say), transferred. */
  port: MessagePort | null;
}

/** What the module must export. */
export interface WorkerTestModule {
  installInWorker(port: MessagePort | null): void | Promise<void>;
}

/** The name of the page's global. */
export const WORKER_TEST_HOOK_GLOBAL = '__MAXL_WORKER_TEST_HOOK__';

/** The page's end: sends the hook to the worker if a test set one. Call it only under import.meta.env.DEV. */
export function sendWorkerTestHook(worker: Worker): void {
  const hook = (globalThis as Record<string, unknown>)[WORKER_TEST_HOOK_GLOBAL] as { module?: unknown; port?: unknown } | undefined;
  if (!hook) return;
  if (typeof hook.module !== 'string') throw new Error(`${WORKER_TEST_HOOK_GLOBAL}.module must be a module URL, not ${typeof hook.module}`);
  const port = hook.port instanceof MessagePort ? hook.port : null;
  const message: WorkerTestHook = { type: 'worker-test-hook', module: hook.module, port };
  worker.postMessage(message, port ? [port] : []);
}

export function isWorkerTestHook(data: unknown): data is WorkerTestHook {
  return typeof data === 'object' && data !== null && (data as { type?: unknown }).type === 'worker-test-hook';
}

/** The worker's end: imports the module and installs it. */
export async function loadWorkerTestHook(hook: WorkerTestHook): Promise<void> {
  const module = (await import(/* @vite-ignore */ hook.module)) as Partial<WorkerTestModule>;
  if (typeof module.installInWorker !== 'function') throw new Error(`the worker test module ${hook.module} exports no installInWorker(port)`);
  await module.installInWorker(hook.port);
}
