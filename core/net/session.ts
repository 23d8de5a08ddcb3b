/**
 * A session with one device over one link (docs/protocol.md):
 *  - opening: HELLO_REQUEST, then the device's HELLO and one READER per reader,
 *    refusing a peer of another protocol version with a message naming both;
 *  - reliable, ordered sending: sequence numbers, a window of unacknowledged
 *    frames, go-back-N resends on BAD_CRC, OUT_OF_ORDER or a timeout;
 *  - clock sync: periodic pings folded into a ClockSync;
 *  - receiving: acks and nacks, pongs, STATUS, SAMPLES;
 *  - health: silence for too long means the link is lost; an unasked-for HELLO
 *    means the device rebooted (and forgot its queue).
 */
import { MaxlError } from '../errors.ts';
import { seededRandom } from '../random.ts';
import type { Scheduler, Timer } from '../time/scheduler.ts';
import type { ClockMap } from './clockMap.ts';
import { ClockSync } from './clockSync.ts';
import { encodeFrame, FrameReceiver, type RawPacket } from './frame.ts';
import type { Link } from './link.ts';
import type { SendResult, StreamDevice } from './streamDevice.ts';
import { decodePayload, type Message, type MessageOf, WireError } from './messages.ts';
import { MessageType, NackReason, nameOf, NO_SESSION_DETAIL, PROTOCOL_VERSION, ReaderKind, type NackReasonName, type ReaderKindName } from './protocol.ts';
import { silenceVerdict } from './silenceCheck.ts';

export interface ReaderInfo {
  index: number;
  name: string;
  kind: ReaderKindName;
  /** values per sample, for sensors */
  channels: number;
}

export interface DeviceInfo {
  name: string;
  protocol: number;
  firmware: string;
  clockHz: number;
  segmentCapacity: number;
  eventCapacity: number;
  readers: ReaderInfo[];
}

export type { SendResult };

/** What probe() learned: where the device is, and the sequence number it expected next (null: no session). */
export interface ProbeResult {
  status: MessageOf<'STATUS'> | null;
  expectedSeq: number | null;
}

export interface SessionOptions {
  /** ms-scale timings, in µs */
  helloTimeout_us: number;
  /**
   * Resend unacknowledged frames after this long (µs) at least; 2·RTT when larger.
   * A corrupted frame is nacked at once; this catches the rarer loss of a frame
   * or of its nack, and must fit within the streamer's lead time.
   */
  resendAfter_us: number;
  /** the link is lost after this long without a frame from the device (µs) */
  silence_us: number;
  /** ping period (µs) during a session */
  pingEvery_us: number;
  /** ping period (µs) during a burst (pingBurst), to fit a clock model quickly */
  burstPingEvery_us: number;
  /** a session pings at the burst period for this long after it opens (µs) */
  youngFor_us: number;
  /** unacknowledged frames in flight at most */
  window: number;
}

export const DEFAULT_SESSION: SessionOptions = {
  helloTimeout_us: 1_000_000,
  resendAfter_us: 4_000,
  silence_us: 300_000,
  pingEvery_us: 25_000,
  burstPingEvery_us: 4_000,
  youngFor_us: 120_000_000,
  window: 8,
};

/** frameLoss averages over about this many recent frames. */
const LOSS_AVERAGE_FRAMES = 256;

export interface SessionEvents {
  status?(status: MessageOf<'STATUS'>, at_us: number): void;
  samples?(samples: MessageOf<'SAMPLES'>, at_us: number): void;
  /** the link went silent, or broke: the session is over */
  lost?(reason: string): void;
  /** the device sent HELLO unasked: it restarted and lost everything queued */
  rebooted?(): void;
  /** a frame the session could not use (bad CRC from the device, malformed…) */
  wireError?(error: WireError): void;
}

interface Outgoing {
  seq: number;
  frame: Uint8Array;
  message: Message;
  /** the last transmission, for the resend timer */
  sentAt: number;
  /** the first transmission, for how long the frame has gone unacknowledged */
  firstSentAt: number;
  resolve(result: SendResult): void;
}

export class DeviceSession implements StreamDevice {
  readonly link: Link;
  readonly clock = new ClockSync();
  info: DeviceInfo | null = null;
  /** Free queue space the device last reported. */
  freeSegments = 0;
  /** Free event entries the device last reported, less those taken since (takeEventRoom). */
  private freeEvents = 0;
  lastStatus: MessageOf<'STATUS'> | null = null;
  /** Frames resent so far (diagnostics). */
  resends = 0;
  /** The sequence number of the last message given to send(). */
  lastSentSeq = 0;
  state: 'closed' | 'opening' | 'open' | 'lost' = 'closed';

  private readonly scheduler: Scheduler;
  private readonly options: SessionOptions;
  private readonly events: SessionEvents;
  private writer: WritableStreamDefaultWriter<Uint8Array> | null = null;
  private reader: ReadableStreamDefaultReader<Uint8Array> | null = null;
  /** While probe() waits: what it does with the device's answers. */
  private probing: { onAnswer(seq: number, nack: MessageOf<'NACK'> | null, statusBefore: MessageOf<'STATUS'> | null): void } | null = null;
  /** While probing: the packet just before this one, if it was a STATUS (a request's STATUS comes right before its ack). */
  private probeStatus: MessageOf<'STATUS'> | null = null;
  private writeChain: Promise<void> = Promise.resolve();
  private nextSeq = 1;
  /** Frames sent and not yet acknowledged, oldest first, then frames waiting for the window. */
  private inFlight: Outgoing[] = [];
  private waiting: Outgoing[] = [];
  private receiver: FrameReceiver;
  private lastHeard = 0;
  /** When the frame before the last one came (author µs). */
  private heardBefore = 0;
  /** The session's timers, by job: one of each at most. */
  private readonly timers: Record<'hello' | 'helloTimeout' | 'ping' | 'silence' | 'resend', Timer | null> = {
    hello: null,
    helloTimeout: null,
    ping: null,
    silence: null,
    resend: null,
  };
  private pendingHello: { resolve(info: DeviceInfo): void; reject(err: Error): void; hello?: MessageOf<'HELLO'>; readers: ReaderInfo[] } | null = null;
  /** Pings awaiting their pong: when each was written (author µs), its frame's length in bytes, and whether it was sent again. */
  private pings = new Map<number, { at: number; frameBytes: number; resent: boolean }>();
  /** The share of recent frames found corrupted (frameLoss). */
  private lossAverage = 0;
  private lastHelloRequestAt = -Infinity;
  private burstUntil = -Infinity;
  private openedAt = 0;
  private nextPingId = 1;

  constructor(link: Link, scheduler: Scheduler, events: SessionEvents = {}, options: Partial<SessionOptions> = {}) {
    this.link = link;
    this.scheduler = scheduler;
    this.events = events;
    this.options = { ...DEFAULT_SESSION, ...options };
    this.receiver = new FrameReceiver(
      (p, frameBytes) => {
        this.noteFrame(false);
        this.onPacket(p, frameBytes);
      },
      (e) => {
        this.noteFrame(true);
        this.events.wireError?.(e);
      },
    );
  }

  get label(): string {
    return this.info?.name ?? this.link.label ?? 'device';
  }

  /**
   * When the device last sent a frame before the latest one (author µs, at its
   * arrival): after a restart is detected (the latest frame), the last moment it was
   * known to run its old session.
   */
  get heardBefore_us(): number {
    return this.heardBefore;
  }

  /** Round-trip time, µs (median of recent pings). */
  get rtt_us(): number {
    return this.clock.rtt;
  }

  /**
   * Opens the session: says hello, learns the device and its readers, and starts
   * pinging. Rejects with a MaxlError if the device does not answer, or speaks
   * another protocol version.
   */
  async open(): Promise<DeviceInfo> {
    this.state = 'opening';
    this.attach();
    this.lastHeard = this.scheduler.now();
    const info = await new Promise<DeviceInfo>((resolve, reject) => {
      this.pendingHello = { resolve, reject, readers: [] };
      const hello = encodeFrame(0, { type: 'HELLO_REQUEST', protocol: PROTOCOL_VERSION });
      // Said again every 100 ms until answered: the first may be lost, or the board still booting.
      const say = () => {
        if (!this.pendingHello) return;
        this.lastHelloRequestAt = this.scheduler.now();
        this.write(hello);
        this.timers.hello = this.scheduler.after(100_000, say);
      };
      say();
      this.timers.helloTimeout = this.scheduler.after(this.options.helloTimeout_us, () => {
        if (this.pendingHello) {
          this.pendingHello = null;
          reject(new MaxlError('DEVICE_UNAVAILABLE', `no answer to hello within ${this.options.helloTimeout_us / 1000} ms on ${this.link.label ?? 'a link'}: is it a MAXL device, at the right baud rate?`));
        }
      });
    });
    this.info = info;
    this.state = 'open';
    this.openedAt = this.scheduler.now();
    this.schedulePing();
    this.scheduleHealth();
    return info;
  }

  /** Sends a message reliably, in order. Resolves when the device acknowledged or refused it. */
  send(message: Message): Promise<SendResult> {
    if (this.state !== 'open') return Promise.reject(new MaxlError('DEVICE_UNAVAILABLE', `${this.label}: the session is ${this.state}`));
    return new Promise((resolve) => {
      const seq = this.nextSeq;
      this.lastSentSeq = seq;
      this.nextSeq = (this.nextSeq + 1) & 0xff;
      const out: Outgoing = { seq, frame: encodeFrame(seq, message), message, sentAt: 0, firstSentAt: NaN, resolve };
      this.waiting.push(out);
      this.fillWindow();
    });
  }

  // --- what the streamer sees (StreamDevice) ---

  get isOpen(): boolean {
    return this.state === 'open';
  }

  get rttHigh_us(): number {
    return this.clock.rttHigh || 0;
  }

  get clockMap(): ClockMap | null {
    return this.clock.clock;
  }

  takeEventRoom(count: number): boolean {
    if (count > this.freeEvents) return false;
    this.freeEvents -= count;
    return true;
  }

  /** How long the oldest unacknowledged frame has waited for its ack since first sent (µs), 0 if none. */
  get oldestUnacked_us(): number {
    const oldest = this.inFlight[0];
    return oldest ? this.scheduler.now() - oldest.firstSentAt : 0;
  }

  /**
   * The share of recent frames found corrupted (0 on a clean link): an exponential
   * average over the last ~LOSS_AVERAGE_FRAMES frames, each counted 1 if it failed its
   * check here (a bad CRC, a broken frame from the device) or was nacked BAD_CRC by the
   * device (one of ours, corrupted on the way), 0 if it came through. Corruption is
   * measured, not resends: on a slow link (an Uno's 25 kB/s UART) acks come late and
   * the resend timer fires with nothing lost; counting those resends as loss lengthened
   * the leads, which queued more bytes, which made more late acks (the feed-limit test's
   * spiral stalled).
   */
  get frameLoss(): number {
    return this.lossAverage;
  }

  private noteFrame(corrupted: boolean): void {
    this.lossAverage += ((corrupted ? 1 : 0) - this.lossAverage) / LOSS_AVERAGE_FRAMES;
  }

  /** The resend timeout in force (µs). */
  get resendAfter_us(): number {
    return Math.max(this.options.resendAfter_us, 2 * (this.clock.rttHigh || 0));
  }

  /** Pings five times as often for `duration_us`, so the clock model converges quickly (begin() does this). */
  pingBurst(duration_us: number): void {
    this.burstUntil = this.scheduler.now() + duration_us;
  }

  /** Frames queued or in flight. */
  get backlog(): number {
    return this.inFlight.length + this.waiting.length;
  }

  /**
   * Asks a device, before this session says hello, where it is: a STATUS, read
   * without disturbing it. The device may still hold an older session (after a
   * link cut) whose next sequence number this session does not know: a
   * STATUS_REQUEST out of order is answered OUT_OF_ORDER with the number
   * expected (or, on a frame cut in half by the cut, BAD_CRC with it), and is
   * sent again with it; a duplicate's old answer says nothing, and the request
   * goes again 16 numbers on (docs/protocol.md §3). Resolves with the STATUS and
   * the sequence number the device expected (every frame before it was handled),
   * or with nulls when the device has no session (it restarted: it knows nothing
   * of the path). Rejects with DEVICE_UNAVAILABLE if it does not answer.
   */
  probe(timeout_us = 500_000): Promise<ProbeResult> {
    if (this.state !== 'closed') throw new MaxlError('RECOVERY_ORDER', `${this.label}: probe() comes before open()`);
    this.attach();
    return new Promise((resolve, reject) => {
      let timer: Timer | null = null;
      let asked = 0;
      const finish = (result: ProbeResult | Error) => {
        this.probing = null;
        timer?.cancel();
        if (result instanceof Error) reject(result);
        else resolve(result);
      };
      const ask = (seq: number) => {
        asked = seq & 0xff;
        this.probeStatus = null;
        this.write(encodeFrame(asked, { type: 'STATUS_REQUEST' }));
      };
      this.probing = {
        onAnswer: (seq, nack, statusBefore) => {
          const reason = nack ? nameOf(NackReason, nack.reason) : null;
          // Acked right after a STATUS: the request was handled as new, so the device
          // expected its number. (A board that is not idle also sends STATUS every
          // 100 ms: only the one just before the ack is the answer.)
          if (reason === 'OUT_OF_ORDER' && nack!.detail === NO_SESSION_DETAIL) finish({ status: null, expectedSeq: null });
          else if (reason === 'BAD_CRC') ask(nack!.seq); // it names the number expected
          else if (seq !== asked) return; // an answer to the old session's traffic, late
          else if (!nack && statusBefore) finish({ status: statusBefore, expectedSeq: asked });
          else if (reason === 'OUT_OF_ORDER') ask(nack!.detail);
          else ask(seq + 16); // a duplicate's old answer, or a refusal: try further on
        },
      };
      timer = this.scheduler.after(timeout_us, () =>
        finish(new MaxlError('DEVICE_UNAVAILABLE', `${this.link.label ?? 'a device'} did not answer a status request within ${timeout_us / 1000} ms: is it connected and powered?`)),
      );
      ask(0);
    });
  }

  /**
   * Stops timers and releases the link's streams, so that another session can take
   * the link over; `closeLink` (default true) also closes the link itself.
   */
  async close(closeLink = true): Promise<void> {
    this.stopTimers();
    this.state = 'closed';
    this.probing = null;
    // An open() still waiting for the hello fails now: its timeout timer is gone.
    if (this.pendingHello) {
      this.pendingHello.reject(new MaxlError('DEVICE_UNAVAILABLE', `${this.label}: the session was closed before the device said hello`));
      this.pendingHello = null;
    }
    for (const o of [...this.inFlight, ...this.waiting]) o.resolve({ ok: false, reason: 'UNKNOWN_MESSAGE', detail: 0, unsent: true });
    this.inFlight = [];
    this.waiting = [];
    // Writes already chained go out first.
    await this.writeChain.catch(() => undefined);
    this.detach();
    if (closeLink) await this.link.close?.();
  }

  /** Takes the link's writer and starts reading, once per session. */
  private attach(): void {
    if (this.writer) return;
    if (this.link.writable.locked || this.link.readable.locked) {
      throw new MaxlError('DEVICE_UNAVAILABLE', `${this.link.label ?? 'a link'} is in use by another session: end() the author that holds it, or reconnect() with it`);
    }
    this.writer = this.link.writable.getWriter();
    this.reader = this.link.readable.getReader();
    void this.readLoop(this.reader);
  }

  // --- sending ---

  private write(frame: Uint8Array, stamp?: () => void): void {
    const writer = this.writer;
    if (!writer) return;
    this.writeChain = this.writeChain.then(async () => {
      stamp?.();
      try {
        await writer.write(frame);
      } catch (err) {
        this.lose(`write failed: ${(err as Error).message}`);
      }
    });
  }

  private fillWindow(): void {
    while (this.waiting.length > 0 && this.inFlight.length < this.options.window) {
      const out = this.waiting.shift() as Outgoing;
      this.transmit(out);
      this.inFlight.push(out);
      if (this.inFlight.length === 1) this.armResend();
    }
  }

  private transmit(out: Outgoing): void {
    out.sentAt = this.scheduler.now();
    if (Number.isNaN(out.firstSentAt)) out.firstSentAt = out.sentAt;
    // A ping is stamped as its first copy enters the link. (If that copy was lost, the
    // stamp is early: the exchange then looks slow, which the envelopes ignore, and its
    // round trip counts the resend's wait, which rtt leaves out: `resent`.)
    const pingId = out.message.type === 'PING' ? out.message.pingId : -1;
    const frameBytes = out.frame.length;
    const resent = out.firstSentAt !== out.sentAt;
    // A first copy is stamped afresh, even if its id is still held: a ping whose pong was
    // lost stays in `pings`, and 65 535 pings later (262 s at 4 ms) its id comes round
    // again; kept, that stale stamp made the new exchange's round trip minutes long.
    if (pingId >= 0 && resent) {
      const ping = this.pings.get(pingId);
      if (ping) ping.resent = true;
    }
    this.write(out.frame, pingId >= 0 && !resent ? () => this.pings.set(pingId, { at: this.scheduler.now(), frameBytes, resent: false }) : undefined);
  }

  /** Go-back-N: resend every frame in flight from `seq` on. */
  private resendFrom(seq: number): void {
    const at = this.inFlight.findIndex((o) => o.seq === seq);
    if (at < 0) return;
    for (let k = at; k < this.inFlight.length; k++) {
      this.resends++;
      this.transmit(this.inFlight[k]);
    }
    this.armResend();
  }

  /** Completes every frame in flight up to and including `seq` (acks are cumulative: the device works in order). */
  private complete(seq: number, result: SendResult): void {
    const at = this.inFlight.findIndex((o) => o.seq === seq);
    if (at < 0) return;
    const done = this.inFlight.splice(0, at + 1);
    done.forEach((o, k) => o.resolve(k === done.length - 1 ? result : { ok: true }));
    this.armResend();
    this.fillWindow();
  }

  // --- receiving ---

  private async readLoop(reader: ReadableStreamDefaultReader<Uint8Array>): Promise<void> {
    try {
      for (;;) {
        const { value, done } = await reader.read();
        if (done) break;
        if (value) this.receiver.push(value);
      }
      this.lose('the link closed');
    } catch (err) {
      this.lose(`the link failed: ${(err as Error).message}`);
    } finally {
      try {
        reader.releaseLock();
      } catch {
        // close() released it
      }
    }
  }

  private onPacket(p: RawPacket, frameBytes: number): void {
    const now = this.scheduler.now();
    this.heardBefore = this.lastHeard;
    this.lastHeard = now;
    let message: Message;
    try {
      const channels = p.typeCode === MessageType.SAMPLES ? (this.info?.readers[p.payload[0]]?.channels ?? 0) : 0;
      message = decodePayload(p.typeCode, p.payload, { positionSlots: 0, channels }, p.seq);
    } catch (err) {
      if (err instanceof WireError) {
        this.events.wireError?.(err);
        return;
      }
      throw err;
    }
    if (this.probing) {
      const before = this.probeStatus;
      this.probeStatus = message.type === 'STATUS' ? message : null;
      if (message.type === 'ACK') this.probing.onAnswer(message.ackSeq, null, before);
      else if (message.type === 'NACK') this.probing.onAnswer(message.seq, message, before);
      return;
    }
    switch (message.type) {
      case 'HELLO':
        this.onHello(message);
        break;
      case 'READER':
        this.onReader(message);
        break;
      case 'ACK':
        this.freeSegments = message.freeSegments;
        this.freeEvents = message.freeEvents;
        this.complete(message.ackSeq, { ok: true });
        break;
      case 'NACK':
        this.onNack(message);
        break;
      case 'PONG': {
        const sent = this.pings.get(message.pingId);
        if (sent !== undefined) {
          this.pings.delete(message.pingId);
          // Each frame's own time on a UART, if the link has one (clockSync.ts, "Frames take time on a UART").
          const byte_us = this.link.uartByteTime_us ?? 0;
          this.clock.add({
            authorSend: sent.at,
            authorReceive: now,
            deviceReceive: message.rxTime,
            deviceReply: message.txTime,
            pingOnWire_us: sent.frameBytes * byte_us,
            pongOnWire_us: frameBytes * byte_us,
            resent: sent.resent,
          });
        }
        break;
      }
      case 'STATUS':
        this.lastStatus = message;
        this.events.status?.(message, now);
        break;
      case 'SAMPLES':
        this.events.samples?.(message, now);
        break;
      default:
        this.events.wireError?.(new WireError('UNKNOWN_MESSAGE', `${message.type} is not a device-to-author message`));
    }
  }

  private onHello(hello: MessageOf<'HELLO'>): void {
    const pending = this.pendingHello;
    if (!pending) {
      // The answer to a repeated hello request, late: nothing happened.
      if (this.scheduler.now() - this.lastHelloRequestAt < Math.max(500_000, 4 * (this.clock.rttHigh || 0))) return;
      // Unasked: the device restarted.
      if (this.state === 'open') {
        this.events.rebooted?.();
        this.lose('the device restarted');
      }
      return;
    }
    if (hello.protocol !== PROTOCOL_VERSION) {
      this.pendingHello = null;
      pending.reject(
        new MaxlError(
          'VERSION_MISMATCH',
          `device "${hello.name}" speaks MAXL protocol ${hello.protocol} (firmware ${hello.fwMajor}.${hello.fwMinor}.${hello.fwPatch}); this author speaks protocol ${PROTOCOL_VERSION}. Update the firmware or the workbench so they match.`,
        ),
      );
      return;
    }
    pending.hello = hello;
    this.finishHello();
  }

  private onReader(reader: MessageOf<'READER'>): void {
    const pending = this.pendingHello;
    if (!pending) return;
    pending.readers[reader.index] = {
      index: reader.index,
      name: reader.name,
      kind: (nameOf(ReaderKind, reader.kind) ?? 'position') as ReaderKindName,
      channels: reader.channels,
    };
    this.finishHello();
  }

  private finishHello(): void {
    const pending = this.pendingHello;
    const hello = pending?.hello;
    if (!pending || !hello) return;
    const readers = pending.readers.filter(Boolean);
    if (readers.length < hello.readerCount) return;
    this.pendingHello = null;
    this.freeSegments = hello.segmentCapacity;
    this.freeEvents = hello.eventCapacity;
    pending.resolve({
      name: hello.name,
      protocol: hello.protocol,
      firmware: `${hello.fwMajor}.${hello.fwMinor}.${hello.fwPatch}`,
      clockHz: hello.clockHz,
      segmentCapacity: hello.segmentCapacity,
      eventCapacity: hello.eventCapacity,
      readers,
    });
  }

  private onNack(nack: MessageOf<'NACK'>): void {
    const reason = nameOf(NackReason, nack.reason) ?? 'MALFORMED';
    if (reason === 'OUT_OF_ORDER' && nack.detail === NO_SESSION_DETAIL) {
      // The device has no session: it restarted (and forgot its queue) without a HELLO we saw.
      if (this.state === 'open') {
        this.events.rebooted?.();
        this.lose('the device restarted (it no longer knows this session)');
      }
      return;
    }
    if (reason === 'BAD_CRC' || reason === 'OUT_OF_ORDER') {
      if (reason === 'BAD_CRC') this.noteFrame(true);
      // The device expects `seq` (BAD_CRC) or `detail` (OUT_OF_ORDER): everything before it arrived.
      const expected = reason === 'OUT_OF_ORDER' ? nack.detail & 0xff : nack.seq;
      const before = (expected - 1) & 0xff;
      if (this.inFlight.some((o) => o.seq === before)) this.complete(before, { ok: true });
      this.resendFrom(expected);
      return;
    }
    if (reason === 'VERSION_MISMATCH' && this.pendingHello) return; // the HELLO that follows says more
    this.complete(nack.seq, { ok: false, reason, detail: nack.detail });
  }

  // --- timers ---

  /**
   * Pings at pingEvery_us on average, each interval drawn uniformly from ±25 % of
   * it. The dither matters: a link that moves data in fixed slots (USB's 1 ms
   * frames) adds a wait that depends on when in the slot a ping is sent. Pings at a
   * fixed period (a multiple of the slot) would all see the same wait, and the
   * fastest exchanges, which clock sync relies on, would never come.
   */
  private schedulePing(): void {
    const random = seededRandom(hashString(this.link.label ?? 'link'));
    const tick = () => {
      if (this.state !== 'open') return;
      // Pings do not queue behind a backlog: a late ping would only add noise.
      if (this.backlog < this.options.window) {
        const pingId = this.nextPingId;
        this.nextPingId = (this.nextPingId % 0xffff) + 1;
        // The reply waits 0–2 ms: see PING in docs/protocol.md §4.
        void this.send({ type: 'PING', pingId, replyAfter: Math.floor(random() * 2000) });
      }
      // Fast while the model is young (it converges with the number of exchanges),
      // then at the session's pace: burstPingEvery_us while the session is young (youngFor_us, two minutes by default), then pingEvery_us.
      const age = this.scheduler.now() - this.openedAt;
      const young = age < this.options.youngFor_us || this.scheduler.now() < this.burstUntil ? this.options.burstPingEvery_us : Infinity;
      const every = Math.min(young, this.options.pingEvery_us);
      this.timers.ping = this.scheduler.after(every * (0.75 + 0.5 * random()), tick);
    };
    tick();
  }

  /** Checks now and then that the device still talks (any frame will do: acks, pongs, status); silenceCheck.ts. */
  private scheduleHealth(): void {
    const period = this.options.silence_us / 4;
    let due = this.scheduler.now() + period;
    let heldBack = false;
    const check = () => {
      if (this.state !== 'open') return;
      const now = this.scheduler.now();
      const verdict = silenceVerdict({ now_us: now, due_us: due, lastHeard_us: this.lastHeard, silence_us: this.options.silence_us, previousHeldBack: heldBack });
      if (verdict === 'lost') {
        this.lose(`no frame from the device for ${((now - this.lastHeard) / 1000).toFixed(0)} ms`);
        return;
      }
      heldBack = verdict === 'held-back';
      due = now + period;
      this.timers.silence = this.scheduler.after(period, check);
    };
    this.timers.silence = this.scheduler.after(period, check);
  }

  /**
   * Keeps one timer on the oldest frame in flight: when it has waited resendAfter_us
   * for its ack, everything from it on is sent again. Armed when a frame goes out
   * with none in flight before it, moved on as acks come, dropped when none is left.
   */
  private armResend(): void {
    this.timers.resend?.cancel();
    this.timers.resend = null;
    const oldest = this.inFlight[0];
    if (!oldest || this.state !== 'open') return;
    this.timers.resend = this.scheduler.at(oldest.sentAt + this.resendAfter_us, () => {
      this.timers.resend = null;
      const first = this.inFlight[0];
      // Compare with the very sum the timer was set for: now - sentAt can round below
      // resendAfter_us, and the timer would then fire again at once, forever.
      if (first && this.scheduler.now() >= first.sentAt + this.resendAfter_us) this.resendFrom(first.seq);
      else this.armResend();
    });
  }

  private stopTimers(): void {
    for (const key of Object.keys(this.timers) as Array<keyof typeof this.timers>) {
      this.timers[key]?.cancel();
      this.timers[key] = null;
    }
  }

  private lose(reason: string): void {
    if (this.state === 'lost' || this.state === 'closed') return;
    this.state = 'lost';
    this.stopTimers();
    if (this.pendingHello) {
      this.pendingHello.reject(new MaxlError('DEVICE_UNAVAILABLE', `${this.label}: ${reason}`));
      this.pendingHello = null;
    }
    for (const o of [...this.inFlight, ...this.waiting]) o.resolve({ ok: false, reason: 'UNKNOWN_MESSAGE', detail: 0, unsent: true });
    this.inFlight = [];
    this.waiting = [];
    this.detach();
    this.events.lost?.(reason);
  }

  /** Releases the link's streams (without closing the link), so that another session can take it over. */
  private detach(): void {
    const writer = this.writer;
    const reader = this.reader;
    this.writer = null;
    this.reader = null;
    try {
      writer?.releaseLock();
    } catch {
      // already released
    }
    try {
      // A read still pending rejects: the read loop then ends quietly (the session is over).
      reader?.releaseLock();
    } catch {
      // already released
    }
  }
}

/** A 32-bit FNV-1a hash, to seed a session's dither from its link's label. */
function hashString(text: string): number {
  let h = 0x811c9dc5;
  for (let i = 0; i < text.length; i++) {
    h ^= text.charCodeAt(i);
    h = Math.imul(h, 0x01000193) >>> 0;
  }
  return h;
}
