/**
 * The view canvas as OrbitControls sees it inside the view worker, where there is
 * no DOM: an event target that the page's pointer, wheel and key events are
 * replayed on (as three.js's offscreen examples do), with the size and position
 * the page last reported.
 *
 * OrbitControls uses of its element: add/removeEventListener (pointerdown,
 * pointercancel, wheel, contextmenu), `ownerDocument` for the drag's pointermove
 * and pointerup and the Control key (here the proxy itself: the page sends them
 * all to this one target), `setPointerCapture` (the page captures the pointer on
 * the real canvas), `style` (cursor, touch-action: the page's CSS sets
 * touch-action), clientWidth/clientHeight and getBoundingClientRect.
 */
import type { ViewInputEvent } from './viewProtocol.ts';

type Listener = (event: ReplayedEvent) => void;

/** An input event as a listener receives it: the page's fields, and no-op default handling (the page did that). */
export type ReplayedEvent = ViewInputEvent & { preventDefault(): void; stopPropagation(): void };

export class ElementProxy {
  private readonly listeners = new Map<string, Set<Listener>>();
  readonly style: Record<string, string> = {};
  clientWidth = 1;
  clientHeight = 1;
  private left = 0;
  private top = 0;

  /** The drag's document-level listeners land here too. */
  get ownerDocument(): ElementProxy {
    return this;
  }

  addEventListener(type: string, listener: Listener): void {
    let set = this.listeners.get(type);
    if (!set) this.listeners.set(type, (set = new Set()));
    set.add(listener);
  }

  removeEventListener(type: string, listener: Listener): void {
    this.listeners.get(type)?.delete(listener);
  }

  setPointerCapture(): void {}
  releasePointerCapture(): void {}
  focus(): void {}

  getBoundingClientRect(): { left: number; top: number; width: number; height: number; right: number; bottom: number; x: number; y: number } {
    const { left, top, clientWidth: width, clientHeight: height } = this;
    return { left, top, width, height, right: left + width, bottom: top + height, x: left, y: top };
  }

  /** Where the canvas is on the page and its CSS size, px. */
  place(left: number, top: number, width: number, height: number): void {
    this.left = left;
    this.top = top;
    this.clientWidth = width;
    this.clientHeight = height;
  }

  /** Replays an event from the page on this element's listeners. */
  dispatch(event: ViewInputEvent): void {
    const set = this.listeners.get(event.type);
    if (!set) return;
    const replayed: ReplayedEvent = { ...event, preventDefault() {}, stopPropagation() {} };
    for (const listener of [...set]) listener(replayed);
  }
}
