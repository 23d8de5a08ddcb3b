/**
 * The page's end of the worker protocol: starts the one MAXL worker, sends
 * commands (transferring streams and buffers), and asks for a snapshot once per
 * animation frame, never twice before the last one came back.
 */
import type { Command, Snapshot, WorkerEvent } from '../worker/protocol.ts';
import { sendWorkerTestHook } from '../worker/workerTestHook.ts';

export type EventHandler = (e: WorkerEvent) => void;

export class WorkerClient {
  private readonly worker: Worker;
  private readonly handlers = new Set<EventHandler>();
  private awaitingSnapshot = false;
  private frameRequest = 0;
  /** Snapshots received (for tests and the bench). */
  snapshots = 0;

  constructor() {
    this.worker = new Worker(new URL('../worker/maxlWorker.ts', import.meta.url), { type: 'module', name: 'maxl' });
    // A test's hook into the worker goes first, before any command (dev server only: docs/test-hooks.md).
    if (import.meta.env.DEV) sendWorkerTestHook(this.worker);
    this.worker.onmessage = (m: MessageEvent<WorkerEvent>) => this.dispatch(m.data);
    this.worker.onerror = (e) => {
      this.dispatch({ type: 'log', entry: { id: -1, at: Date.now(), level: 'error', code: 'WORKER', message: `The MAXL worker failed to start or crashed: ${e.message}. Reload the page.` } });
    };
  }

  send(cmd: Command, transfer: Transferable[] = []): void {
    this.worker.postMessage(cmd, transfer);
  }

  on(handler: EventHandler): () => void {
    this.handlers.add(handler);
    return () => this.handlers.delete(handler);
  }

  /** Starts asking for snapshots every animation frame. */
  startFrames(): void {
    const tick = () => {
      this.frameRequest = requestAnimationFrame(tick);
      if (this.awaitingSnapshot) return;
      this.awaitingSnapshot = true;
      this.send({ type: 'frame' });
    };
    this.frameRequest = requestAnimationFrame(tick);
  }

  stopFrames(): void {
    cancelAnimationFrame(this.frameRequest);
  }

  private dispatch(e: WorkerEvent): void {
    if (e.type === 'snapshot') {
      this.awaitingSnapshot = false;
      this.snapshots++;
    }
    for (const h of this.handlers) h(e);
  }
}

export type { Snapshot };
