/**
 * The view worker: draws the live 3D view (trajectoryView.ts) into the page's two
 * canvases, handed over as OffscreenCanvas, off the page's main thread.
 *
 * Why a worker of its own (docs/design.md, decision 9): without a GPU (SwiftShader
 * here, any software renderer), a canvas drawn on the main thread is read back and
 * composited there, 60–80 ms a frame for a big scene, and the page's input, its
 * readouts and the serial bridge wait behind it. An OffscreenCanvas drawn in a
 * worker is committed from the worker's thread straight to the compositor, so that
 * cost lands here. Not in the core's worker: the author and the simulator must
 * never wait for a draw either.
 *
 * Messages are handled in order, so a query (`query`) answers with the camera as
 * every earlier input event left it.
 */
import { ElementProxy } from './elementProxy.ts';
import { TrajectoryView } from './trajectoryView.ts';
import type { ViewCommand, ViewEvent } from './viewProtocol.ts';

const element = new ElementProxy();
let view: TrajectoryView | null = null;
let lastReport = '';

function post(e: ViewEvent): void {
  (self as unknown as Worker).postMessage(e);
}

/**
 * Tells the page the counts and the tool as drawn, when they changed: after a
 * message, not after each draw (a draw changes only `renders`), so that the page
 * gets no more messages than it sends.
 */
function report(): void {
  if (!view) return;
  const p = view.toolPosition;
  const e: ViewEvent = { type: 'report', stats: view.stats, toolPosition: [p.x, p.y, p.z] };
  const key = JSON.stringify(e);
  if (key === lastReport) return;
  lastReport = key;
  post(e);
}

self.onmessage = (m: MessageEvent<ViewCommand>) => {
  const c = m.data;
  if (c.type === 'init') {
    element.place(c.place.left, c.place.top, c.place.width, c.place.height);
    view = new TrajectoryView(c.canvas, c.overlay, element, c.devicePixelRatio);
    report();
    return;
  }
  if (!view) throw new Error(`the view worker got "${c.type}" before "init"`);
  switch (c.type) {
    case 'place': {
      const resized = c.place.width !== element.clientWidth || c.place.height !== element.clientHeight;
      element.place(c.place.left, c.place.top, c.place.width, c.place.height);
      if (resized) view.resize();
      break;
    }
    case 'input':
      element.dispatch(c.event);
      break;
    case 'snapshot':
      view.applySnapshot(c);
      break;
    case 'preview':
      view.setPreview(c.points, c.coarse, c.coarseIndex, c.tolerance_mm);
      view.fit();
      break;
    case 'work-area':
      view.setWorkArea(c.min, c.max);
      break;
    case 'origin':
      view.setOrigin(c.origin);
      break;
    case 'mode':
      view.setMode(c.mode);
      break;
    case 'fit':
      view.fit();
      break;
    case 'query':
      post({ type: 'answer', id: c.id, cameraPose: view.cameraPose, workAreaBounds: view.workAreaBounds });
      break;
  }
  report();
};
