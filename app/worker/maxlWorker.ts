/**
 * The workbench's one dedicated worker: the MAXL core runs here, and the page
 * only draws and handles input. Messages in and out are typed in protocol.ts.
 */
/// <reference lib="webworker" />
import { transferablesOf, type Command, type WorkerEvent } from './protocol.ts';
import { Workbench } from './workbench.ts';
import { isWorkerTestHook, loadWorkerTestHook } from './workerTestHook.ts';

const scope = self as unknown as DedicatedWorkerGlobalScope;

const workbench = new Workbench((e: WorkerEvent, transfer?: Transferable[]) => scope.postMessage(e, transfer ?? transferablesOf(e)));

function handle(cmd: Command): void {
  try {
    workbench.handle(cmd);
  } catch (err) {
    workbench.log('error', 'WORKER', `The workbench hit an internal error: ${(err as Error).message ?? String(err)}`);
  }
}

/** Set once a test hook arrives (dev server only): commands wait until its module is installed, in order. */
let afterHook: Promise<void> | null = null;

scope.onmessage = (message: MessageEvent<Command>) => {
  const data: unknown = message.data;
  if (import.meta.env.DEV && isWorkerTestHook(data)) {
    afterHook = loadWorkerTestHook(data).catch((err: unknown) => {
      workbench.log('error', 'TEST_HOOK', `The worker test hook failed: ${(err as Error).message ?? String(err)}`);
    });
    return;
  }
  if (afterHook) afterHook = afterHook.then(() => handle(message.data));
  else handle(message.data);
};
