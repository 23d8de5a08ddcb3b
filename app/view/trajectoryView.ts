/**
 * The live 3D view of the trajectory: the locked path (historical and
 * transmitted), the queue (planned and unplanned), a job's preview, the work
 * area, the origin, and the tool at the author's real-time estimate.
 *
 * Everything big lives in BufferGeometry that is appended to with update ranges,
 * never rebuilt. The tool and the origin are drawn on a 2D overlay every frame; the
 * WebGL scene is drawn only when it changed, and no more often than the GPU keeps
 * up with: after each draw, the time until the next frame says what a draw costs,
 * and a costly scene (a million segments on a software renderer) is redrawn at most
 * every few such costs while it streams. Camera moves always draw at once.
 *
 * It runs in the view worker (viewWorker.ts), on the page's canvases handed over
 * as OffscreenCanvas, with OrbitControls on an ElementProxy that the page's input
 * events are replayed on.
 */
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import type { ElementProxy } from './elementProxy.ts';
import type { CameraMode, CameraPose, ViewSnapshot, ViewStats } from './viewProtocol.ts';
import { AppendOnlyPath } from './appendOnlyPath.ts';
import { JobPreview } from './jobPreview.ts';
import { QueueLines } from './queueLines.ts';
import { SCENE_COLORS, STATE_COLORS } from './colors.ts';
import { ToolOverlay } from './toolOverlay.ts';
import { WorkArea } from './workArea.ts';

export type { CameraMode };

/** ms: at most 20 draws a second of streaming content on a software renderer. */
const SOFTWARE_MIN_DRAW_INTERVAL_MS = 50;
/** ms: the tool's overlay at most 30 times a second there. */
const SOFTWARE_MIN_OVERLAY_INTERVAL_MS = 33;

export class TrajectoryView {
  readonly renderer: THREE.WebGLRenderer;
  private readonly scene = new THREE.Scene();
  private readonly camera = new THREE.PerspectiveCamera(35, 1, 0.1, 100_000);
  private readonly controls: OrbitControls;
  private readonly locked = new AppendOnlyPath(STATE_COLORS.historical, STATE_COLORS.transmitted);
  private readonly queue = new QueueLines(STATE_COLORS.planned, STATE_COLORS.unplanned);
  private readonly preview = new JobPreview(STATE_COLORS.unplanned);
  private readonly overlay: ToolOverlay;
  private readonly originPosition = new THREE.Vector3();
  private readonly workArea = new WorkArea();
  private runtimeId = -1;
  private dirty = true;
  private mode: CameraMode = 'top';
  private frameHandle = 0;
  /** ms a scene draw is allowed to wait for, after the last one, while content streams. */
  private drawInterval = 0;
  /** ms: the least time between draws of streaming content (a software renderer's floor). */
  private readonly minDrawInterval: number;
  private lastDraw = -Infinity;
  private overlayHandle = 0;
  private lastOverlay = -Infinity;
  /** ms: the least time between overlay draws while the tool moves (a software renderer's floor). */
  private readonly minOverlayInterval: number;
  private urgent = false;
  private measuring = false;
  private width = 1;
  private height = 1;
  /** Renders so far, and the snapshot-to-pixels bookkeeping the tests and the bench read. */
  renders = 0;
  readonly toolPosition = new THREE.Vector3();

  constructor(
    canvas: OffscreenCanvas,
    overlayCanvas: OffscreenCanvas,
    private readonly element: ElementProxy,
    devicePixelRatio: number,
  ) {
    this.overlay = new ToolOverlay(overlayCanvas);
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: false });
    // A software renderer (no GPU: SwiftShader, llvmpipe) draws every pixel on the CPU,
    // and with software compositing the page waits for each frame: draw it at 3/4 of
    // the CSS pixels there. A GPU gets the display's full resolution.
    const software = softwareRenderer(this.renderer.getContext());
    this.renderer.setPixelRatio(software ? 0.75 : Math.min(2, devicePixelRatio));
    // In a worker, a draw no longer holds up the page, so nothing paces it any more but
    // this: a software renderer spends CPU time on every pixel of every draw (and on
    // reading it back), which the core's worker and the page share on a small machine.
    // While a job streams the paths change every frame; they are redrawn at most 20
    // times a second there (the tool and the locked-ahead path, on the overlay, still
    // move every frame; camera moves still draw at once).
    this.minDrawInterval = software ? SOFTWARE_MIN_DRAW_INTERVAL_MS : 0;
    this.minOverlayInterval = software ? SOFTWARE_MIN_OVERLAY_INTERVAL_MS : 0;
    this.scene.background = new THREE.Color(SCENE_COLORS.background);
    this.scene.add(
      this.workArea.group,
      this.preview.group,
      this.locked.historicalLines,
      this.locked.transmittedLines,
      this.queue.lines,
    );
    this.controls = new OrbitControls(this.camera, element as unknown as HTMLElement);
    this.controls.enableDamping = false;
    this.controls.screenSpacePanning = true;
    this.controls.addEventListener('change', () => {
      this.updateScale();
      this.requestRender(true);
    });
    this.setMode('top');
    this.resize();
  }

  get cameraMode(): CameraMode {
    return this.mode;
  }

  get stats(): ViewStats {
    return {
      lockedSegments: this.locked.segments,
      historicalSegments: this.locked.historicalSegments,
      queueSegments: this.queue.count,
      previewSegments: this.preview.segments,
      transmittedLength_mm: this.locked.transmittedLength(),
      renders: this.renders,
    };
  }

  /** Where the camera is and what it looks at, mm (for the page's tests and benches). */
  get cameraPose(): CameraPose {
    return { position: this.camera.position.toArray(), target: this.controls.target.toArray(), up: this.camera.up.toArray() };
  }

  /** The work area's bounds as drawn, mm: [x0, y0, x1, y1] (a rail has a small y extent). */
  get workAreaBounds(): number[] {
    const b = this.workArea.box;
    return [b.min.x, b.min.y, b.max.x, b.max.y];
  }

  /** The work area (soft limits), mm, per motion axis; infinite sides fall back to the content. */
  setWorkArea(min: readonly number[], max: readonly number[]): void {
    this.workArea.set(min, max);
    this.requestRender();
  }

  setOrigin(origin: readonly number[]): void {
    this.originPosition.set(origin[0] ?? 0, origin[1] ?? 0, origin[2] ?? 0);
    this.drawOverlay();
  }

  applySnapshot(s: ViewSnapshot): void {
    if (s.runtimeId !== this.runtimeId) {
      this.runtimeId = s.runtimeId;
      this.locked.clear();
      this.queue.clear();
    }
    const historical = this.locked.historicalSegments;
    if (s.locked.length > 0) this.locked.append(s.lockedFrom, s.locked);
    this.locked.setHistorical(s.historical);
    if (s.queue && s.queueStates) this.queue.set(s.queue, s.queueStates);
    this.preview.setFed(s.jobFed);
    const p = s.position;
    const moved = this.toolPosition.x !== (p[0] ?? 0) || this.toolPosition.y !== (p[1] ?? 0) || this.toolPosition.z !== (p[2] ?? 0);
    this.toolPosition.set(p[0] ?? 0, p[1] ?? 0, p[2] ?? 0);
    if (moved || s.locked.length > 0 || historical !== this.locked.historicalSegments) this.requestOverlay();
    if (s.locked.length > 0 || s.queue || historical !== this.locked.historicalSegments) this.requestRender();
  }

  /** Shows a job's whole path (and its coarse copy for the overview), drawn in this task. */
  setPreview(vertices: Float32Array, coarse: Float32Array, coarseIndex: Uint32Array, tolerance_mm: number): void {
    this.preview.set(vertices, coarse, coarseIndex, tolerance_mm);
    this.updateScale();
    this.dirty = true;
    this.renderNow();
  }

  clearPreview(): void {
    this.preview.clear();
    this.requestRender();
  }

  setMode(mode: CameraMode): void {
    this.mode = mode;
    // The top view is a map: a drag pans it (it never tilts it edge-on); in 3D a drag orbits.
    this.controls.enableRotate = mode === '3d';
    this.controls.mouseButtons.LEFT = mode === 'top' ? THREE.MOUSE.PAN : THREE.MOUSE.ROTATE;
    this.controls.touches.ONE = mode === 'top' ? THREE.TOUCH.PAN : THREE.TOUCH.ROTATE;
    this.camera.up.set(0, mode === 'top' ? 1 : 0, mode === 'top' ? 0 : 1);
    this.fit();
  }

  /** Frames everything there is: work area, paths, preview, tool. */
  fit(): void {
    const box = new THREE.Box3();
    box.union(this.workArea.box);
    if (!this.locked.bounds.box.isEmpty()) box.union(this.locked.bounds.box);
    if (!this.preview.bounds.box.isEmpty() && this.preview.segments > 0) box.union(this.preview.bounds.box);
    box.expandByPoint(this.toolPosition);
    if (box.isEmpty()) box.set(new THREE.Vector3(-50, -50, 0), new THREE.Vector3(50, 50, 0));
    const center = box.getCenter(new THREE.Vector3());
    const size = box.getSize(new THREE.Vector3());
    const aspect = this.camera.aspect || 1;
    const halfFov = THREE.MathUtils.degToRad(this.camera.fov / 2);
    const fitHeight = Math.max(size.y, size.x / aspect, 1) * 0.56;
    const distance = this.mode === 'top' ? fitHeight / Math.tan(halfFov) : (size.length() * 0.6) / Math.sin(halfFov);
    this.controls.target.copy(center);
    if (this.mode === 'top') this.camera.position.set(center.x, center.y, center.z + distance);
    else this.camera.position.set(center.x + distance * 0.55, center.y - distance * 0.65, center.z + distance * 0.55);
    this.camera.near = Math.max(0.01, distance / 1000);
    this.camera.far = distance * 100;
    this.camera.updateProjectionMatrix();
    this.controls.update();
    this.updateScale();
    this.requestRender(true);
  }

  /**
   * Draws the scene at the next animation frame, or later if the last draws were
   * costly (`now`: a camera move, drawn at once regardless).
   */
  requestRender(now = false): void {
    this.dirty = true;
    // A camera move while a streaming draw waits out its interval takes the next frame.
    if (now) this.urgent = true;
    if (this.frameHandle) return;
    const tick = () => {
      this.frameHandle = 0;
      if (!this.urgent && performance.now() - this.lastDraw < this.drawInterval) {
        this.frameHandle = requestAnimationFrame(tick);
        return;
      }
      this.urgent = false;
      this.renderNow();
    };
    this.frameHandle = requestAnimationFrame(tick);
  }

  renderNow(): void {
    this.drawOverlay();
    if (!this.dirty) return;
    this.dirty = false;
    const start = performance.now();
    this.renderer.render(this.scene, this.camera);
    this.lastDraw = start;
    this.renders++;
    // What the draw cost shows in when the next frame comes.
    if (!this.measuring) {
      this.measuring = true;
      requestAnimationFrame(() => {
        this.measuring = false;
        const cost = performance.now() - start;
        this.drawInterval = Math.max(this.minDrawInterval, cost > 40 ? Math.min(3000, 4 * cost) : 0);
      });
    }
  }

  /** Pixels per mm at the orbit target, for the preview's choice of detail. */
  private updateScale(): void {
    const distance = this.camera.position.distanceTo(this.controls.target);
    const visibleHeight = 2 * distance * Math.tan(THREE.MathUtils.degToRad(this.camera.fov / 2));
    this.preview.setScale(this.height / Math.max(visibleHeight, 1e-9));
  }

  /**
   * Draws the overlay (the tool, the locked-ahead path) at the next animation frame,
   * once however many snapshots came, and on a software renderer at most 30 times a
   * second: each overlay frame is composited in software too.
   */
  private requestOverlay(): void {
    if (this.overlayHandle) return;
    const tick = () => {
      this.overlayHandle = 0;
      if (performance.now() - this.lastOverlay < this.minOverlayInterval) {
        this.overlayHandle = requestAnimationFrame(tick);
        return;
      }
      this.drawOverlay();
    };
    this.overlayHandle = requestAnimationFrame(tick);
  }

  private drawOverlay(): void {
    this.lastOverlay = performance.now();
    this.overlay.draw(this.camera, this.toolPosition, this.originPosition, this.locked.transmittedVertices(), this.width, this.height);
  }

  dispose(): void {
    cancelAnimationFrame(this.frameHandle);
    cancelAnimationFrame(this.overlayHandle);
    this.controls.dispose();
    this.renderer.dispose();
  }

  /** The canvas's CSS size (the element proxy's), px: the drawing buffer follows at the pixel ratio. */
  resize(): void {
    const width = Math.max(1, this.element.clientWidth);
    const height = Math.max(1, this.element.clientHeight);
    this.renderer.setSize(width, height, false);
    this.width = width;
    this.height = height;
    this.overlay.resize(width, height, this.renderer.getPixelRatio());
    this.camera.aspect = width / height;
    this.camera.updateProjectionMatrix();
    this.requestRender();
  }
}

/** Whether WebGL is drawn in software: no GPU, or one the browser refused. */
function softwareRenderer(gl: WebGLRenderingContext | WebGL2RenderingContext): boolean {
  const info = gl.getExtension('WEBGL_debug_renderer_info');
  const name = info ? String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL)) : '';
  return /swiftshader|llvmpipe|software/i.test(name);
}
