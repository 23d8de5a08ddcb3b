/**
 * Jog input from buttons and keys: a tap moves one step; holding (longer than
 * HOLD_AFTER_MS) streams motion until release. The release's event time travels
 * with the stop, so the worker can measure the stop latency from the real input.
 */
import type { Command } from '../worker/protocol.ts';

export const HOLD_AFTER_MS = 250;

interface Press {
  key: string;
  held: boolean;
  timer: ReturnType<typeof setTimeout>;
}

export class JogInput {
  private press: Press | null = null;

  constructor(
    private readonly send: (cmd: Command) => void,
    private readonly settings: () => { step_mm: number; speed: number; axes: number },
  ) {}

  /** A direction pressed: `axis` index and sign. `key` names the button or key, so its release ends it. */
  down(key: string, axis: number, sign: 1 | -1): void {
    if (this.press) return;
    const { step_mm, speed, axes } = this.settings();
    if (axis >= axes) return;
    const direction = new Array<number>(axes).fill(0);
    direction[axis] = sign;
    this.send({ type: 'jog-step', delta: direction.map((d) => d * step_mm), speed });
    const press: Press = {
      key,
      held: false,
      timer: setTimeout(() => {
        press.held = true;
        this.send({ type: 'jog-start', direction, speed });
      }, HOLD_AFTER_MS),
    };
    this.press = press;
  }

  /** The release; `timeStamp` is the event's (performance.now() scale). */
  up(key: string, timeStamp: number): void {
    const press = this.press;
    if (!press || press.key !== key) return;
    this.press = null;
    clearTimeout(press.timer);
    if (press.held) this.send({ type: 'jog-stop', releasedAt: performance.timeOrigin + timeStamp });
  }

  /** Focus left the page while held: stop as if released now. */
  cancel(): void {
    if (this.press) this.up(this.press.key, performance.now());
  }
}

/** The jog keys: arrows move x and y, PageUp/PageDown the third axis. */
export const JOG_KEYS: Record<string, { axis: number; sign: 1 | -1 }> = {
  ArrowRight: { axis: 0, sign: 1 },
  ArrowLeft: { axis: 0, sign: -1 },
  ArrowUp: { axis: 1, sign: 1 },
  ArrowDown: { axis: 1, sign: -1 },
  PageUp: { axis: 2, sign: 1 },
  PageDown: { axis: 2, sign: -1 },
};
