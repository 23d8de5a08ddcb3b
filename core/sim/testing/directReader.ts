/**
 * The real reader firmware (a wasm example) answering frames one at a time,
 * with no link, scheduler or plant in between: for tests that feed it many
 * frames and only need its answers (ACK or NACK), fast.
 *
 * `send` delivers one frame at an author time and runs the firmware's loop at
 * that instant until the frame is answered; the device clock is the author
 * clock (offset 0, no drift), so device µs = author µs.
 */
import { readFile } from 'node:fs/promises';
import { encodeFrame, FrameReceiver } from '../../net/frame.ts';
import { decodePayload, type Message } from '../../net/messages.ts';
import { PROTOCOL_VERSION, ReaderKind } from '../../net/protocol.ts';
import { UNCONNECTED } from '../device/deviceHardware.ts';
import { PUBLIC_FIRMWARE_DIR } from '../device/nodeWasmLoader.ts';
import { WasmDevice } from '../device/wasmDevice.ts';

export type Answer = { type: 'ACK' } | { type: 'NACK'; reason: number; detail: number };

export class DirectReader {
  private seq = 0;
  private readonly replies: Message[] = [];
  private readonly receiver = new FrameReceiver(
    (p) => this.replies.push(decodePayload(p.typeCode, p.payload, { positionSlots: 1, channels: 3 }, p.seq)),
    (error) => {
      throw error;
    },
  );
  private constructor(private readonly device: WasmDevice) {}

  /** The Stepper example, in session, with its one position reader on slot 0. */
  static async stepper(): Promise<DirectReader> {
    const module = new WebAssembly.Module(await readFile(`${PUBLIC_FIRMWARE_DIR}Stepper.wasm`));
    let reader: DirectReader | null = null;
    const device = await WasmDevice.instantiate(module, {
      name: 'stepper',
      clock: { offset_us: 0, ppm: 0 },
      hardware: UNCONNECTED,
      serialOut: (bytes) => reader?.receiver.push(bytes),
    });
    reader = new DirectReader(device);
    device.start(0);
    reader.expectAck(reader.send({ type: 'HELLO_REQUEST', protocol: PROTOCOL_VERSION }, 0), 'HELLO_REQUEST');
    reader.expectAck(reader.send({ type: 'SUBSCRIBE', reader: 0, kind: ReaderKind.position, slot: 0 }, 0), 'SUBSCRIBE');
    return reader;
  }

  /** Delivers one frame at author time t_us (never earlier than the last) and returns the device's answer to it. */
  send(message: Message, t_us: number): Answer {
    const seq = this.seq;
    this.seq = (this.seq + 1) & 0xff;
    this.replies.length = 0;
    this.device.receive(encodeFrame(seq, message), t_us);
    // A frame longer than one loop's read takes a few loops, all at this instant.
    for (let i = 0; i < 64; i++) {
      const answer = this.replies.find((r) => (r.type === 'ACK' && r.ackSeq === seq) || (r.type === 'NACK' && r.seq === seq));
      if (answer?.type === 'ACK') return { type: 'ACK' };
      if (answer?.type === 'NACK') return { type: 'NACK', reason: answer.reason, detail: answer.detail };
      this.device.receive(new Uint8Array(0), t_us);
    }
    throw new Error(`the device did not answer ${message.type} (seq ${seq})`);
  }

  private expectAck(answer: Answer, what: string): void {
    if (answer.type !== 'ACK') throw new Error(`${what}: ${JSON.stringify(answer)}`);
  }
}
