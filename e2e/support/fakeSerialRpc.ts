/**
 * Calls between the fake serial's pieces (the page and the MAXL worker call the
 * fake boards' Node process over a WebSocket each): a request carries an id, its
 * answer the same id, a value or a DOMException's name and message (so the app
 * sees the errors a browser throws). Text messages of JSON.
 */
export interface RpcRequest {
  id: number;
  call: string;
  args?: unknown;
}

export type RpcAnswer = { id: number; ok: true; value: unknown } | { id: number; ok: false; name: string; message: string };

/** A port as the boards list it: its place among the granted ports and its USB ids. */
export interface FakePortInfo {
  index: number;
  usbVendorId: number;
  usbProductId: number;
}

/** What the page hands the worker's half over the hook's channel. */
export interface FakeBoardsAddress {
  /** The session's URL without path or role: `ws://127.0.0.1:PORT/?session=…&preset=…&granted=N&serialInWorkers=0|1`. */
  session: string;
}

/** The session's socket URL for `path` (`/control`, `/port`) with more query fields. */
export function sessionUrl(session: string, path: string, more: Record<string, string>): string {
  const url = new URL(session);
  url.pathname = path;
  for (const [k, v] of Object.entries(more)) url.searchParams.set(k, v);
  return url.href;
}

/** One end of a text channel: a browser WebSocket, or the Node side's (fakeBoardsProcess.ts adapts it). */
export interface TextChannel {
  send(text: string): void;
  onText(listener: (text: string) => void): void;
}

/** A browser WebSocket as a TextChannel (binary messages are not this channel's). */
export function textChannelOf(socket: WebSocket): TextChannel {
  return {
    send: (text) => socket.send(text),
    onText: (listener) =>
      socket.addEventListener('message', (m: MessageEvent) => {
        if (typeof m.data === 'string') listener(m.data);
      }),
  };
}

/** Opens a WebSocket to `url` and resolves once it is connected. */
export function connectSocket(url: string): Promise<WebSocket> {
  const socket = new WebSocket(url);
  return new Promise((resolve, reject) => {
    socket.addEventListener('open', () => resolve(socket), { once: true });
    socket.addEventListener('error', () => reject(new Error(`the fake boards at ${url} could not be reached (is their process running? e2e/support/fakeBoards.ts)`)), { once: true });
  });
}

/** The calling end: `call(name, args)` resolves with the other end's answer. */
export function rpcClient(channel: TextChannel): <T>(call: string, args?: unknown) => Promise<T> {
  let nextId = 1;
  const waiting = new Map<number, { resolve: (v: unknown) => void; reject: (e: unknown) => void }>();
  channel.onText((text) => {
    const answer = JSON.parse(text) as RpcAnswer;
    const w = waiting.get(answer.id);
    if (!w || !('ok' in answer)) return;
    waiting.delete(answer.id);
    if (answer.ok) w.resolve(answer.value);
    else w.reject(new DOMException(answer.message, answer.name));
  });
  return <T>(call: string, args?: unknown) =>
    new Promise<T>((resolve, reject) => {
      const id = nextId++;
      waiting.set(id, { resolve: resolve as (v: unknown) => void, reject });
      channel.send(JSON.stringify({ id, call, args } satisfies RpcRequest));
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

/** The answering end: `handler` returns a value or throws an RpcError. */
export function rpcServer(channel: TextChannel, handler: (call: string, args: unknown) => Promise<unknown>): void {
  channel.onText(async (text) => {
    const request = JSON.parse(text) as RpcRequest;
    if (typeof request?.call !== 'string') return;
    try {
      const value = await handler(request.call, request.args);
      channel.send(JSON.stringify({ id: request.id, ok: true, value } satisfies RpcAnswer));
    } catch (err) {
      const e = err as { domName?: string; name?: string; message?: string };
      channel.send(JSON.stringify({ id: request.id, ok: false, name: e.domName ?? e.name ?? 'Error', message: e.message ?? String(err) } satisfies RpcAnswer));
    }
  });
}
