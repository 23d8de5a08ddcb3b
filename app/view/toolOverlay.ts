/**
 * The tool (and the origin) drawn on a 2D canvas over the WebGL one. The tool
 * moves every frame; the paths do not need to be drawn again for that, which
 * matters when the paths are large and the GPU is slow (or software).
 *
 * The transmitted segments are drawn here too, wide: minimal buffering keeps only
 * a few milliseconds of motion locked ahead of the tool, which a 1-pixel WebGL
 * line under the tool's dot hides.
 */
import * as THREE from 'three';
import { SCENE_COLORS, STATE_COLORS } from './colors.ts';

/** px: the width of the locked-ahead path, and of its white halo. */
const LOCKED_WIDTH = 6;
const LOCKED_HALO = 10;

export class ToolOverlay {
  private readonly g: OffscreenCanvasRenderingContext2D;
  private readonly v = new THREE.Vector3();

  constructor(private readonly canvas: OffscreenCanvas) {
    this.g = canvas.getContext('2d') as OffscreenCanvasRenderingContext2D;
  }

  resize(width: number, height: number, pixelRatio: number): void {
    this.canvas.width = Math.round(width * pixelRatio);
    this.canvas.height = Math.round(height * pixelRatio);
    this.g.setTransform(pixelRatio, 0, 0, pixelRatio, 0, 0);
  }

  draw(camera: THREE.Camera, tool: THREE.Vector3, origin: THREE.Vector3, transmitted: Float32Array, width: number, height: number): void {
    const g = this.g;
    g.clearRect(0, 0, width, height);
    this.dot(camera, origin, width, height, 4.5, SCENE_COLORS.origin);
    this.ring(camera, tool, width, height, 8, SCENE_COLORS.tool);
    // Over the tool's ring: at a few ms of motion the locked path is often shorter than the ring is wide.
    this.lockedPath(camera, transmitted, width, height);
  }

  /** The tool: a ring, so that the locked path starting inside it stays visible. */
  private ring(camera: THREE.Camera, p: THREE.Vector3, width: number, height: number, r: number, color: string): void {
    if (!this.circle(camera, p, width, height, r)) return;
    const g = this.g;
    g.lineWidth = 6;
    g.strokeStyle = 'rgba(255,255,255,0.9)';
    g.stroke();
    g.lineWidth = 3;
    g.strokeStyle = color;
    g.stroke();
  }

  /** The transmitted segments (2 vertices × xyz each), wide, on a white halo. */
  private lockedPath(camera: THREE.Camera, vertices: Float32Array, width: number, height: number): void {
    if (vertices.length === 0) return;
    const g = this.g;
    g.beginPath();
    for (let i = 0; i < vertices.length; i += 6) {
      const a = this.screen(camera, vertices[i], vertices[i + 1], vertices[i + 2], width, height);
      g.moveTo(a[0], a[1]);
      const b = this.screen(camera, vertices[i + 3], vertices[i + 4], vertices[i + 5], width, height);
      g.lineTo(b[0], b[1]);
    }
    g.lineCap = 'round';
    g.lineJoin = 'round';
    g.lineWidth = LOCKED_HALO;
    g.strokeStyle = 'rgba(255,255,255,0.85)';
    g.stroke();
    g.lineWidth = LOCKED_WIDTH;
    g.strokeStyle = STATE_COLORS.transmitted;
    g.stroke();
  }

  private screen(camera: THREE.Camera, x: number, y: number, z: number, width: number, height: number): [number, number] {
    const s = this.v.set(x, y, z).project(camera);
    return [((s.x + 1) / 2) * width, ((1 - s.y) / 2) * height];
  }

  private dot(camera: THREE.Camera, p: THREE.Vector3, width: number, height: number, r: number, color: string): void {
    if (!this.circle(camera, p, width, height, r)) return;
    const g = this.g;
    g.fillStyle = color;
    g.fill();
    g.lineWidth = 2;
    g.strokeStyle = 'rgba(255,255,255,0.9)';
    g.stroke();
  }

  /** Begins a circle path of radius r (px) around p on screen; false if p is outside the view's depth. */
  private circle(camera: THREE.Camera, p: THREE.Vector3, width: number, height: number, r: number): boolean {
    const s = this.v.copy(p).project(camera);
    if (s.z < -1 || s.z > 1) return false;
    this.g.beginPath();
    this.g.arc(((s.x + 1) / 2) * width, ((1 - s.y) / 2) * height, r, 0, Math.PI * 2);
    return true;
  }
}
