/**
 * An emulated Arduino Uno for hardware-in-the-loop tests: the real firmware's AVR
 * build (scripts/firmware-hil.sh) in libsimavr (firmware/hil/simavr_uno_pty.c),
 * its UART on a pseudo-terminal that the core opens with `serialport`, its STEP
 * and DIR pins recorded edge by edge.
 *
 * Time, in lockstep: the author's clock is a VirtualScheduler whose µs are the
 * AVR's cycles / 16 since its reset. The harness runs the AVR up to a granted
 * cycle and reports it ("C <cycle>"); this driver then moves the author's clock
 * there (running the core's timers due by then), lets Node's I/O turn once,
 * and grants the next quantum. Neither side can run ahead of the other by more
 * than a quantum, however slowly the host runs either, and the bytes still cross
 * a real pty at the Uno's 250 000 baud (one byte per 40 µs of AVR time). What
 * real time would add, a host that answers late, is then measured in AVR time:
 * the RTT and the steps' timing say how late.
 *
 * Causality, byte by byte: the link from openLink() counts what it has read and
 * what it has written. A grant goes out only once everything the core wrote has
 * reached the pty (so it enters the UART at or after the cycle the author's
 * clock said), and the clock moves to a reported cycle only once every byte the
 * board wrote before it has been read (so the core receives it at or after the
 * time it was sent, late by at most a quantum, as on a real link).
 */
import { spawn, type ChildProcess } from 'node:child_process';
import { existsSync, readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { VirtualScheduler } from '../time/virtualScheduler.ts';
import type { Link } from '../net/link.ts';
import { openSerialportLink } from '../net/serialportLink.ts';

export const AVR_HZ = 16_000_000;
export const CYCLES_PER_US = AVR_HZ / 1e6;
const BOARD_JSON = fileURLToPath(new URL('../../firmware/build/hil/board.json', import.meta.url));

/** A rising STEP edge: the AVR cycle it came at and the DIR level then. */
export interface StepEdge {
  cycle: number;
  dir: number;
}

export interface UnoBoard {
  /** the pty's path: open it as the board's serial port */
  readonly ptyPath: string;
  /** the author's clock: AVR µs since reset */
  readonly scheduler: VirtualScheduler;
  readonly edges: readonly StepEdge[];
  /** the cycle at which the sketch's micros() read 0 (null until Timer 0 first overflows) */
  readonly micros0Cycle: number | null;
  /** grants answered, and the real ms the whole lockstep has taken */
  readonly quanta: number;
  /**
   * Opens the pty with `serialport` at the Uno's baud rate, as a board's port;
   * the lockstep follows the bytes this link carries (see the top of the file).
   */
  openLink(): Promise<Link>;
  /** Runs the board until the author's clock reaches `t_us`. */
  runUntil(t_us: number): Promise<void>;
  stop(): Promise<void>;
}

export interface UnoBoardOptions {
  /** AVR µs per lockstep grant. Default 250. */
  quantum_us?: number;
}

interface BoardBuild {
  elf: string;
  harness: string;
  overflowCount: number;
}

/** The build of scripts/firmware-hil.sh, or an error that says loudly what is missing. */
export function boardBuild(): BoardBuild {
  if (!existsSync(BOARD_JSON)) {
    throw new Error(
      `HIL: ${BOARD_JSON} is missing. Build it with 'bash scripts/firmware-hil.sh --build' (needs simavr, libsimavr-dev and the AVR toolchain: bash scripts/install-system-deps.sh)`,
    );
  }
  const build = JSON.parse(readFileSync(BOARD_JSON, 'utf8')) as BoardBuild;
  for (const f of [build.elf, build.harness]) if (!existsSync(f)) throw new Error(`HIL: ${f} is missing; run bash scripts/firmware-hil.sh --build`);
  return build;
}

export async function startUnoBoard(options: UnoBoardOptions = {}): Promise<UnoBoard> {
  const build = boardBuild();
  const quantumCycles = Math.round((options.quantum_us ?? 250) * CYCLES_PER_US);
  const scheduler = new VirtualScheduler(0);
  const child: ChildProcess = spawn(build.harness, [build.elf, '--overflow-count', String(build.overflowCount), '--lockstep', '1'], {
    stdio: ['pipe', 'pipe', 'pipe'],
  });
  const edges: StepEdge[] = [];
  let micros0Cycle: number | null = null;
  let quanta = 0;
  let cycle = 0;
  let target_us = 0;
  let stopped = false;
  let stderr = '';
  let waiters: Array<{ at_us: number; resolve: () => void; reject: (e: Error) => void }> = [];
  let died: Error | null = null;
  let chain = Promise.resolve();
  // the lockstep's view of the link's bytes
  let linkOpen = false;
  let bytesRead = 0;
  let readWaiter: (() => void) | null = null;
  const writes = new Set<Promise<void>>();
  /** Resolves once `n` bytes have been read from the pty, or the link is closed. */
  const readAtLeast = (n: number) =>
    new Promise<void>((resolve) => {
      const check = () => (!linkOpen || bytesRead >= n ? (readWaiter = null, resolve()) : (readWaiter = check));
      check();
    });

  const grant = () => {
    if (stopped) return;
    // Run ahead of the author only up to what a test has asked for.
    if (cycle / CYCLES_PER_US >= target_us) return;
    child.stdin!.write(`G ${cycle + quantumCycles}\n`);
  };
  /** The AVR reached `c`: bring the author's clock there, let I/O turn, grant the next quantum. */
  const reached = (c: number, boardBytes: number) => {
    chain = chain.then(async () => {
      await readAtLeast(boardBytes); // the board's bytes of the last quantum, at the clock of its end
      cycle = c;
      quanta++;
      await scheduler.runUntil(c / CYCLES_PER_US);
      await new Promise((r) => setImmediate(r));
      await Promise.all([...writes]); // the core's bytes are in the pty before the board runs on
      const now_us = c / CYCLES_PER_US;
      waiters = waiters.filter((w) => (w.at_us <= now_us ? (w.resolve(), false) : true));
      grant();
    });
  };

  const ptyPath = await new Promise<string>((resolve, reject) => {
    let pending = '';
    child.on('error', (e) => reject(new Error(`HIL: cannot start the simavr harness ${build.harness}: ${e.message}`)));
    child.on('exit', (code) => {
      if (stopped) return;
      died = new Error(`HIL: the simavr harness exited (${code}): ${stderr}`);
      reject(died);
      for (const w of waiters.splice(0)) w.reject(died);
    });
    child.stderr!.on('data', (d: Buffer) => (stderr = (stderr + d.toString()).slice(-4000)));
    child.stdout!.on('data', (d: Buffer) => {
      pending += d.toString();
      const lines = pending.split('\n');
      pending = lines.pop() ?? '';
      for (const line of lines) {
        const f = line.split(' ');
        if (f[0] === 'S') edges.push({ cycle: Number(f[1]), dir: Number(f[2]) });
        else if (f[0] === 'C') reached(Number(f[1]), Number(f[2]));
        else if (f[0] === 'PTY') resolve(f[1]);
        else if (f[0] === 'MICROS0') micros0Cycle = Number(f[1]);
      }
    });
  });

  return {
    ptyPath,
    scheduler,
    edges,
    get micros0Cycle() {
      return micros0Cycle;
    },
    get quanta() {
      return quanta;
    },
    async openLink() {
      const port = await openSerialportLink(ptyPath);
      linkOpen = true;
      const reader = port.readable.getReader();
      const writer = port.writable.getWriter();
      const readable = new ReadableStream<Uint8Array>({
        async pull(controller) {
          const { value, done } = await reader.read().catch(() => ({ value: undefined, done: true as const }));
          if (done || !value) {
            linkOpen = false;
            readWaiter?.();
            controller.close();
            return;
          }
          bytesRead += value.length;
          controller.enqueue(value);
          readWaiter?.();
        },
        cancel: () => reader.cancel(),
      });
      const writable = new WritableStream<Uint8Array>({
        write(chunk) {
          const w = writer.write(chunk);
          writes.add(w);
          void w.catch(() => undefined).finally(() => writes.delete(w));
          return w;
        },
      });
      return {
        readable,
        writable,
        label: port.label,
        bytesPerSecond: port.bytesPerSecond,
        uartByteTime_us: port.uartByteTime_us,
        close: async () => {
          linkOpen = false;
          readWaiter?.();
          await port.close?.();
        },
      };
    },
    runUntil(t_us: number) {
      return new Promise<void>((resolve, reject) => {
        if (died) return reject(died);
        if (cycle / CYCLES_PER_US >= t_us) return resolve();
        waiters.push({ at_us: t_us, resolve, reject });
        const idle = target_us <= cycle / CYCLES_PER_US;
        target_us = Math.max(target_us, t_us);
        if (idle) grant();
      });
    },
    async stop() {
      if (stopped) return;
      stopped = true;
      child.stdin!.write('Q\n');
      child.stdin!.end();
      await new Promise<void>((resolve) => {
        if (child.exitCode !== null) return resolve();
        const t = setTimeout(() => child.kill('SIGKILL'), 2000);
        child.on('exit', () => (clearTimeout(t), resolve()));
      });
    },
  };
}
