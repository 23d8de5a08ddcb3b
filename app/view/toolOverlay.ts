/**
 * The tool (and the origin) drawn on a 2D canvas over the WebGL one. The tool
 * moves every frame; the paths do not need to be drawn again for that, which
 * matters when the paths are large and the GPU is slow (or software).
 */
import * as THREE from 'three';
import { SCENE_COLORS } from './colors.ts';

export class ToolOverlay {
  private readonly g: CanvasRenderingContext2D;
  private readonly v = new THREE.Vector3();

  constructor(private readonly canvas: HTMLCanvasElement) {
    this.g = canvas.getContext('2d') as CanvasRenderingContext2D;
  }

  resize(width: number, height: number, pixelRatio: number): void {
    this.canvas.width = Math.round(width * pixelRatio);
    this.canvas.height = Math.round(height * pixelRatio);
    this.g.setTransform(pixelRatio, 0, 0, pixelRatio, 0, 0);
  }

  draw(camera: THREE.Camera, tool: THREE.Vector3, origin: THREE.Vector3, width: number, height: number): void {
    const g = this.g;
    g.clearRect(0, 0, width, height);
    this.dot(camera, origin, width, height, 4.5, SCENE_COLORS.origin);
    this.dot(camera, tool, width, height, 7, SCENE_COLORS.tool);
  }

  private dot(camera: THREE.Camera, p: THREE.Vector3, width: number, height: number, r: number, color: string): void {
    const s = this.v.copy(p).project(camera);
    if (s.z < -1 || s.z > 1) return;
    const x = ((s.x + 1) / 2) * width;
    const y = ((1 - s.y) / 2) * height;
    const g = this.g;
    g.beginPath();
    g.arc(x, y, r, 0, Math.PI * 2);
    g.fillStyle = color;
    g.fill();
    g.lineWidth = 2;
    g.strokeStyle = 'rgba(255,255,255,0.9)';
    g.stroke();
  }
}
