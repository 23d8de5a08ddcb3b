/**
 * The messages between the page and the view worker (app/view/viewWorker.ts),
 * which draws the 3D view into the page's canvases through OffscreenCanvas.
 * Big arrays (the snapshot's new locked segments and queue, a job's preview) are
 * transferred, never copied.
 */

export type CameraMode = 'top' | '3d';

/** The input events OrbitControls reads, with the fields it reads (see elementProxy.ts). */
export interface ViewInputEvent {
  type: 'pointerdown' | 'pointermove' | 'pointerup' | 'pointercancel' | 'wheel' | 'contextmenu' | 'keydown' | 'keyup';
  pointerId: number;
  pointerType: string;
  button: number;
  clientX: number;
  clientY: number;
  pageX: number;
  pageY: number;
  ctrlKey: boolean;
  metaKey: boolean;
  shiftKey: boolean;
  deltaY: number;
  deltaMode: number;
  key: string;
  code: string;
}

/** A snapshot's part that the view draws (protocol.ts `Snapshot` says what each field is). */
export interface ViewSnapshot {
  runtimeId: number;
  position: number[];
  lockedFrom: number;
  locked: Float32Array;
  historical: number;
  queue: Float32Array | null;
  queueStates: Uint8Array | null;
  /** Job moves handed to the queue (0 when no job runs): the preview is drawn from there on. */
  jobFed: number;
}

/** The canvas's place on the page and its CSS size, px. */
export interface ViewPlace {
  left: number;
  top: number;
  width: number;
  height: number;
}

/** page → view worker */
export type ViewCommand =
  | { type: 'init'; canvas: OffscreenCanvas; overlay: OffscreenCanvas; place: ViewPlace; devicePixelRatio: number }
  | { type: 'place'; place: ViewPlace }
  | { type: 'input'; event: ViewInputEvent }
  | ({ type: 'snapshot' } & ViewSnapshot)
  | { type: 'preview'; points: Float32Array; coarse: Float32Array; coarseIndex: Uint32Array; tolerance_mm: number }
  | { type: 'work-area'; min: number[]; max: number[] }
  | { type: 'origin'; origin: number[] }
  | { type: 'mode'; mode: CameraMode }
  | { type: 'fit' }
  /** Asks for the camera and the work area as they are once every earlier command is done. */
  | { type: 'query'; id: number };

/** The counts the legend shows, and the renders so far. */
export interface ViewStats {
  lockedSegments: number;
  historicalSegments: number;
  queueSegments: number;
  previewSegments: number;
  transmittedLength_mm: number;
  renders: number;
}

export interface CameraPose {
  position: number[];
  target: number[];
  up: number[];
}

/** view worker → page */
export type ViewEvent =
  /** After any change: the counts, and where the view drew the tool (mm). */
  | { type: 'report'; stats: ViewStats; toolPosition: number[] }
  | { type: 'answer'; id: number; cameraPose: CameraPose; workAreaBounds: number[] };
