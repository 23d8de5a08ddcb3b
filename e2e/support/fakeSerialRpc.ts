/**
 * Calls between the fake serial's pieces (the page, the MAXL worker, the fake
 * boards' worker): a request carries an id, its answer the same id, a value or a
 * DOMException's name and message (so the app sees the errors a browser throws).
 */
export interface RpcRequest {
  id: number;
  call: string;
  args?: unknown;
}

export type RpcAnswer = { id: number; ok: true; value: unknown } | { id: number; ok: false; name: string; message: string };

interface Endpoint {
  postMessage(message: unknown, transfer: Transferable[]): void;
  addEventListener(type: 'message', listener: (m: MessageEvent) => void): void;
  start?(): void;
}

/** The calling end: `call(name, args)` resolves with the other end's answer. */
export function rpcClient(endpoint: Endpoint): <T>(call: string, args?: unknown) => Promise<T> {
  let nextId = 1;
  const waiting = new Map<number, { resolve: (v: unknown) => void; reject: (e: unknown) => void }>();
  endpoint.addEventListener('message', (m: MessageEvent) => {
    const answer = m.data as RpcAnswer;
    const w = waiting.get(answer.id);
    if (!w || !('ok' in answer)) return;
    waiting.delete(answer.id);
    if (answer.ok) w.resolve(answer.value);
    else w.reject(new DOMException(answer.message, answer.name));
  });
  endpoint.start?.();
  return <T>(call: string, args?: unknown) =>
    new Promise<T>((resolve, reject) => {
      const id = nextId++;
      waiting.set(id, { resolve: resolve as (v: unknown) => void, reject });
      endpoint.postMessage({ id, call, args } satisfies RpcRequest, []);
    });
}

/** A failure the answering end reports as a DOMException of this name. */
export class RpcError extends Error {
  constructor(
    readonly domName: string,
    message: string,
  ) {
    super(message);
  }
}

/** The answering end: `handler` returns a value and what of it to transfer, or throws an RpcError. */
export function rpcServer(endpoint: Endpoint, handler: (call: string, args: unknown) => Promise<{ value: unknown; transfer?: Transferable[] }>): void {
  endpoint.addEventListener('message', async (m: MessageEvent) => {
    const request = m.data as RpcRequest;
    if (typeof request?.call !== 'string') return;
    try {
      const { value, transfer } = await handler(request.call, request.args);
      endpoint.postMessage({ id: request.id, ok: true, value } satisfies RpcAnswer, transfer ?? []);
    } catch (err) {
      const e = err as { domName?: string; name?: string; message?: string };
      endpoint.postMessage({ id: request.id, ok: false, name: e.domName ?? e.name ?? 'Error', message: e.message ?? String(err) } satisfies RpcAnswer, []);
    }
  });
  endpoint.start?.();
}
