/**
 * A minimal author for simulator tests: writes frames to a Link with core/net's
 * codec and collects every frame that comes back, decoded, with the author
 * time it arrived. Not the runtime: no resends, no windows, no clock sync.
 */
import { encodeFrame, FrameReceiver } from '../../net/frame.ts';
import type { Link } from '../../net/link.ts';
import { decodePayload, WireError, type Message } from '../../net/messages.ts';
import type { Scheduler } from '../../time/scheduler.ts';

export interface Received {
  t_us: number;
  seq: number;
  message: Message;
}

export class FrameClient {
  readonly received: Received[] = [];
  readonly errors: Array<{ t_us: number; error: WireError }> = [];
  /** Every byte that arrived, in order (for byte-exact determinism checks). */
  readonly bytes: number[] = [];
  readonly arrivals: Array<{ t_us: number; length: number }> = [];
  private readonly writer: WritableStreamDefaultWriter<Uint8Array>;

  constructor(
    private readonly scheduler: Scheduler,
    readonly link: Link,
    options: {
      /** Sample channels for decoding SAMPLES (default 3). */
      channels?: number;
      /** Keep what arrives in `received`, `bytes` and `arrivals` (default true; benchmarks turn it off). */
      keep?: boolean;
      /** Called with each decoded message as it arrives. */
      onMessage?: (r: Received) => void;
    } = {},
  ) {
    const channels = options.channels ?? 3;
    const keep = options.keep ?? true;
    this.writer = link.writable.getWriter();
    const receiver = new FrameReceiver(
      (p) => {
        let r: Received;
        try {
          r = { t_us: scheduler.now(), seq: p.seq, message: decodePayload(p.typeCode, p.payload, { positionSlots: 0, channels }, p.seq) };
        } catch (error) {
          if (!(error instanceof WireError)) throw error;
          this.errors.push({ t_us: scheduler.now(), error });
          return;
        }
        if (keep) this.received.push(r);
        options.onMessage?.(r);
      },
      (error) => this.errors.push({ t_us: scheduler.now(), error }),
    );
    void (async () => {
      const reader = link.readable.getReader();
      for (;;) {
        const { value, done } = await reader.read();
        if (done) return;
        if (keep) {
          this.arrivals.push({ t_us: scheduler.now(), length: value.length });
          for (const b of value) this.bytes.push(b);
        }
        receiver.push(value);
      }
    })();
  }

  send(seq: number, message: Message): void {
    void this.writer.write(encodeFrame(seq, message));
  }

  /** Received messages of one type. */
  of<T extends Message['type']>(type: T): Array<Received & { message: Extract<Message, { type: T }> }> {
    return this.received.filter((r) => r.message.type === type) as Array<Received & { message: Extract<Message, { type: T }> }>;
  }
}
