/**
 * The workbench's one dedicated worker: the MAXL core runs here, and the page
 * only draws and handles input. Messages in and out are typed in protocol.ts.
 */
/// <reference lib="webworker" />
import { transferablesOf, type Command, type WorkerEvent } from './protocol.ts';
import { Workbench } from './workbench.ts';

const scope = self as unknown as DedicatedWorkerGlobalScope;

const workbench = new Workbench((e: WorkerEvent, transfer?: Transferable[]) => scope.postMessage(e, transfer ?? transferablesOf(e)));

scope.onmessage = (message: MessageEvent<Command>) => {
  try {
    workbench.handle(message.data);
  } catch (err) {
    workbench.log('error', 'WORKER', `The workbench hit an internal error: ${(err as Error).message ?? String(err)}`);
  }
};
