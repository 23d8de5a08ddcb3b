/**
 * A port that outlives sessions. The core's DeviceSession takes a Link, reads it
 * until the session ends, and then closes it. The workbench starts a new runtime
 * whenever the configuration or the set of devices changes, or after STOP, and the
 * boards must stay connected across those: so each runtime gets a fresh Link from
 * `session()`, fed from the one open port underneath.
 *
 * The port's bytes go to the current session only; a closed session's writes are
 * dropped. If the port itself ends or fails, the current session sees its
 * readable fail (and reports the link lost), and so does every later one, and
 * `onBroken` says why in words. `close()` cancels the reading, lets go of both
 * streams and closes what lies underneath (the serial port, for a port the
 * worker opened), so that the port can be opened again.
 */
import type { Link } from '../../core/index.ts';

export class SharedPort {
  readonly label: string;
  readonly bytesPerSecond: number | undefined;
  readonly uartByteTime_us: number | undefined;
  private readonly writer: WritableStreamDefaultWriter<Uint8Array>;
  private current: ReadableStreamDefaultController<Uint8Array> | null = null;
  private failure: Error | null = null;
  private readonly closeUnderlying: (() => Promise<void>) | undefined;
  private reader: ReadableStreamDefaultReader<Uint8Array> | null = null;
  private closing = false;
  /** Called once if the port ends or fails by itself (not on close()), with why. */
  onBroken: ((why: string) => void) | null = null;

  constructor(port: Link) {
    this.label = port.label ?? 'port';
    this.bytesPerSecond = port.bytesPerSecond;
    this.uartByteTime_us = port.uartByteTime_us;
    this.writer = port.writable.getWriter();
    this.closeUnderlying = port.close?.bind(port);
    void this.pump(port.readable);
  }

  /** Whether the port broke (unplugged): new sessions fail at once. */
  get broken(): boolean {
    return this.failure !== null;
  }

  /** A Link for one session. Opening a new one ends the previous one. */
  session(): Link {
    this.endCurrent();
    let controller!: ReadableStreamDefaultController<Uint8Array>;
    const readable = new ReadableStream<Uint8Array>({
      start: (c) => {
        controller = c;
      },
    });
    if (this.failure) controller.error(this.failure);
    else this.current = controller;
    let open = true;
    const writable = new WritableStream<Uint8Array>({
      write: async (chunk) => {
        if (!open) return;
        if (this.failure) throw this.failure;
        await this.writer.write(chunk);
      },
    });
    return {
      readable,
      writable,
      label: this.label,
      bytesPerSecond: this.bytesPerSecond,
      uartByteTime_us: this.uartByteTime_us,
      close: async () => {
        open = false;
        if (this.current === controller) this.endCurrent();
      },
    };
  }

  /** Closes the port for good. */
  async close(): Promise<void> {
    this.closing = true;
    this.endCurrent();
    this.failure ??= new Error('the port was closed');
    try {
      await this.reader?.cancel();
      this.reader?.releaseLock();
    } catch {
      // the port failed already
    }
    try {
      this.writer.releaseLock();
    } catch {
      // a pending write holds it; the port is going anyway
    }
    await this.closeUnderlying?.();
  }

  private endCurrent(): void {
    const c = this.current;
    this.current = null;
    try {
      c?.close();
    } catch {
      // already closed
    }
  }

  private async pump(readable: ReadableStream<Uint8Array>): Promise<void> {
    const reader = readable.getReader();
    this.reader = reader;
    try {
      for (;;) {
        const { value, done } = await reader.read();
        if (done) break;
        if (value && this.current) this.current.enqueue(value);
      }
      this.failure ??= new Error('the port closed (unplugged?)');
    } catch (err) {
      this.failure ??= new Error(`the port failed: ${(err as Error).message ?? String(err)}`);
    }
    if (!this.closing) this.onBroken?.(this.failure.message);
    const c = this.current;
    this.current = null;
    c?.error(this.failure);
  }
}
