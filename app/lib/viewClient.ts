/**
 * The page's end of the view worker (app/view/viewWorker.ts): hands it the view's
 * two canvases (transferControlToOffscreen), forwards what it draws and the
 * input OrbitControls needs, and keeps what the worker last reported for the
 * legend and the tests.
 *
 * Snapshots come from the core's worker to the page, which forwards the view's
 * part here with its arrays transferred, not copied: the hop costs the main
 * thread one small message per frame. A MessageChannel from the core's worker to
 * this one would save that hop, but the page needs every snapshot anyway (the
 * readouts, the job, the devices), and the core would have to split each snapshot
 * in two messages that arrive at two threads out of step; the draw, which is
 * what cost the main thread 60–80 ms, is off it either way.
 */
import type { Snapshot } from '../worker/protocol.ts';
import type { CameraMode, CameraPose, ViewCommand, ViewEvent, ViewInputEvent, ViewPlace, ViewStats } from '../view/viewProtocol.ts';

export interface PreviewArrays {
  points: Float32Array;
  coarse: Float32Array;
  coarseIndex: Uint32Array;
  tolerance_mm: number;
}

type Answer = Extract<ViewEvent, { type: 'answer' }>;

const NO_STATS: ViewStats = { lockedSegments: 0, historicalSegments: 0, queueSegments: 0, previewSegments: 0, transmittedLength_mm: 0, renders: 0 };

export class ViewClient {
  private readonly worker: Worker;
  /** The counts as the worker last reported them. */
  stats: ViewStats = NO_STATS;
  /** Where the worker last drew the tool, mm. */
  readonly toolPosition = { x: 0, y: 0, z: 0 };
  private mode: CameraMode = 'top';
  private place: ViewPlace;
  private readonly pointers = new Set<number>();
  private readonly answers = new Map<number, (a: Answer) => void>();
  private nextQuery = 1;
  private readonly undo: Array<() => void> = [];

  constructor(
    private readonly canvas: HTMLCanvasElement,
    overlay: HTMLCanvasElement,
    onReport: (stats: ViewStats) => void,
    onError: (message: string) => void,
  ) {
    if (typeof canvas.transferControlToOffscreen !== 'function') {
      throw new Error('This browser cannot hand a canvas to a worker (OffscreenCanvas), so the 3D view is not drawn. Use a current Chrome, Edge, Firefox or Safari (17 or later).');
    }
    this.worker = new Worker(new URL('../view/viewWorker.ts', import.meta.url), { type: 'module', name: 'maxl-view' });
    this.worker.onmessage = (m: MessageEvent<ViewEvent>) => {
      const e = m.data;
      if (e.type === 'report') {
        this.stats = e.stats;
        [this.toolPosition.x, this.toolPosition.y, this.toolPosition.z] = e.toolPosition;
        onReport(e.stats);
      } else {
        this.answers.get(e.id)?.(e);
        this.answers.delete(e.id);
      }
    };
    this.worker.onerror = (e) => onError(`The 3D view's worker failed: ${e.message}. Reload the page.`);
    this.place = this.measure();
    const offscreen = canvas.transferControlToOffscreen();
    const offscreenOverlay = overlay.transferControlToOffscreen();
    this.send({ type: 'init', canvas: offscreen, overlay: offscreenOverlay, place: this.place, devicePixelRatio: window.devicePixelRatio }, [offscreen, offscreenOverlay]);

    const resize = new ResizeObserver(() => this.updatePlace());
    resize.observe(canvas);
    this.undo.push(() => resize.disconnect());
    this.listen();
  }

  get cameraMode(): CameraMode {
    return this.mode;
  }

  /** Where the camera is and what it looks at, mm, once the worker has handled everything sent before. */
  get cameraPose(): Promise<CameraPose> {
    return this.ask().then((a) => a.cameraPose);
  }

  /** The work area's bounds as drawn, mm: [x0, y0, x1, y1]. */
  get workAreaBounds(): Promise<number[]> {
    return this.ask().then((a) => a.workAreaBounds);
  }

  /** The view's part of a snapshot; its path arrays move to the worker (they are detached here afterwards). */
  applySnapshot(s: Snapshot): void {
    const transfer = new Set<ArrayBuffer>([s.locked.buffer as ArrayBuffer]);
    if (s.queue) transfer.add(s.queue.buffer as ArrayBuffer);
    if (s.queueStates) transfer.add(s.queueStates.buffer as ArrayBuffer);
    this.send(
      {
        type: 'snapshot',
        runtimeId: s.runtimeId,
        position: Array.from(s.position),
        lockedFrom: s.lockedFrom,
        locked: s.locked,
        historical: s.historical,
        queue: s.queue,
        queueStates: s.queueStates,
        jobFed: s.job && s.jobFed > 0 ? s.jobFed : 0,
      },
      [...transfer],
    );
  }

  /** A job's whole path (moved to the worker), framed once drawn. */
  setPreview(p: PreviewArrays): void {
    this.send({ type: 'preview', points: p.points, coarse: p.coarse, coarseIndex: p.coarseIndex, tolerance_mm: p.tolerance_mm }, [
      p.points.buffer as ArrayBuffer,
      p.coarse.buffer as ArrayBuffer,
      p.coarseIndex.buffer as ArrayBuffer,
    ]);
  }

  setWorkArea(min: number[], max: number[]): void {
    this.send({ type: 'work-area', min, max });
  }

  setOrigin(origin: readonly number[]): void {
    this.send({ type: 'origin', origin: [...origin] });
  }

  setMode(mode: CameraMode): void {
    this.mode = mode;
    this.send({ type: 'mode', mode });
  }

  fit(): void {
    this.send({ type: 'fit' });
  }

  dispose(): void {
    for (const u of this.undo) u();
    this.worker.terminate();
  }

  private send(c: ViewCommand, transfer: Transferable[] = []): void {
    this.worker.postMessage(c, transfer);
  }

  private ask(): Promise<Answer> {
    const id = this.nextQuery++;
    return new Promise((resolve) => {
      this.answers.set(id, resolve);
      this.send({ type: 'query', id });
    });
  }

  private measure(): ViewPlace {
    const r = this.canvas.getBoundingClientRect();
    return { left: r.left, top: r.top, width: this.canvas.clientWidth, height: this.canvas.clientHeight };
  }

  /** Tells the worker where the canvas is, if that changed (a resize, a scroll before a zoom to the cursor). */
  private updatePlace(): void {
    const p = this.measure();
    if (p.left === this.place.left && p.top === this.place.top && p.width === this.place.width && p.height === this.place.height) return;
    this.place = p;
    this.send({ type: 'place', place: p });
  }

  /**
   * Pointer and wheel input on the canvas goes to OrbitControls in the worker. A
   * drag captures the pointer here, so its moves and its release reach the canvas
   * wherever they happen; moves without a button down are not sent. The Control
   * key is sent too: OrbitControls tells a trackpad's pinch (a wheel with ctrlKey
   * and no Control key down) from a Ctrl+wheel by it.
   */
  private listen(): void {
    const c = this.canvas;
    const on = <K extends keyof HTMLElementEventMap>(target: HTMLElement | Window, type: K, handler: (e: HTMLElementEventMap[K]) => void, options?: AddEventListenerOptions) => {
      target.addEventListener(type, handler as EventListener, options);
      this.undo.push(() => target.removeEventListener(type, handler as EventListener, options));
    };
    on(c, 'pointerdown', (e) => {
      this.pointers.add(e.pointerId);
      c.setPointerCapture(e.pointerId);
      this.updatePlace();
      this.input(e);
    });
    on(c, 'pointermove', (e) => {
      if (this.pointers.has(e.pointerId)) this.input(e);
    });
    const up = (e: PointerEvent) => {
      if (!this.pointers.delete(e.pointerId)) return;
      this.input(e);
    };
    on(c, 'pointerup', up);
    on(c, 'pointercancel', up);
    on(c, 'wheel', (e) => {
      e.preventDefault();
      this.updatePlace();
      this.input(e);
    }, { passive: false });
    on(c, 'contextmenu', (e) => e.preventDefault());
    const key = (e: KeyboardEvent) => {
      if (e.key === 'Control') this.input(e);
    };
    on(window, 'keydown', key, { capture: true, passive: true });
    on(window, 'keyup', key, { capture: true, passive: true });
  }

  private input(e: PointerEvent | WheelEvent | KeyboardEvent): void {
    const pointer = e instanceof PointerEvent ? e : null;
    const mouse = e instanceof MouseEvent ? e : null;
    const event: ViewInputEvent = {
      type: e.type as ViewInputEvent['type'],
      pointerId: pointer?.pointerId ?? 0,
      pointerType: pointer?.pointerType ?? 'mouse',
      button: mouse?.button ?? 0,
      clientX: mouse?.clientX ?? 0,
      clientY: mouse?.clientY ?? 0,
      pageX: mouse?.pageX ?? 0,
      pageY: mouse?.pageY ?? 0,
      ctrlKey: e.ctrlKey,
      metaKey: e.metaKey,
      shiftKey: e.shiftKey,
      deltaY: e instanceof WheelEvent ? e.deltaY : 0,
      deltaMode: e instanceof WheelEvent ? e.deltaMode : 0,
      key: e instanceof KeyboardEvent ? e.key : '',
      code: e instanceof KeyboardEvent ? e.code : '',
    };
    this.send({ type: 'input', event });
  }
}
