/**
 * A job's whole path, shown the moment it is loaded, in the unplanned colour:
 * as a line strip over all its points, and as a coarse copy (within a tolerance)
 * drawn instead while the view is zoomed out far enough that the difference is
 * under half a pixel. As the job's moves are handed to the queue, the strips'
 * draw ranges start later; the queue and the locked path draw the rest.
 */
import * as THREE from 'three';
import { Bounds } from './bounds.ts';

export class JobPreview {
  readonly group = new THREE.Group();
  readonly bounds = new Bounds();
  private readonly full: THREE.Line;
  private readonly coarse: THREE.Line;
  private coarseIndex: Uint32Array = new Uint32Array(0);
  private tolerance = 0;
  private points = 0;
  private fed = 0;

  constructor(color: string) {
    const material = new THREE.LineBasicMaterial({ color, transparent: true, opacity: 0.8 });
    this.full = new THREE.Line(new THREE.BufferGeometry(), material);
    this.coarse = new THREE.Line(new THREE.BufferGeometry(), material);
    for (const l of [this.full, this.coarse]) {
      l.frustumCulled = false;
      this.group.add(l);
    }
    this.coarse.visible = false;
  }

  /** (n + 1) × xyz vertices: the tool's start, then each move's end; and the coarse copy. */
  set(vertices: Float32Array, coarse: Float32Array, coarseIndex: Uint32Array, tolerance: number): void {
    this.full.geometry.dispose();
    this.coarse.geometry.dispose();
    this.full.geometry = new THREE.BufferGeometry().setAttribute('position', new THREE.BufferAttribute(vertices, 3));
    this.coarse.geometry = new THREE.BufferGeometry().setAttribute('position', new THREE.BufferAttribute(coarse, 3));
    this.coarseIndex = coarseIndex;
    this.tolerance = tolerance;
    this.points = vertices.length / 3;
    this.bounds.clear();
    this.bounds.addVertices(coarse);
    this.setFed(0);
  }

  clear(): void {
    this.points = 0;
    this.bounds.clear();
    this.full.geometry.setDrawRange(0, 0);
    this.coarse.geometry.setDrawRange(0, 0);
  }

  get segments(): number {
    return Math.max(0, this.points - 1);
  }

  /** Picks the copy to draw for a scale of `pixelsPerMm`. */
  setScale(pixelsPerMm: number): void {
    const coarse = this.tolerance * pixelsPerMm < 0.5 && this.coarseIndex.length < this.points;
    this.coarse.visible = coarse;
    this.full.visible = !coarse;
  }

  /** Moves handed to the queue: the strips are drawn from the last of them on. */
  setFed(moves: number): void {
    if (moves === this.fed && moves !== 0) return;
    this.fed = moves;
    const first = Math.min(moves, this.points);
    this.full.geometry.setDrawRange(first, Math.max(0, this.points - first));
    // First coarse vertex at or after `first`, stepping back one so the strip joins.
    let lo = 0, hi = this.coarseIndex.length;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (this.coarseIndex[mid] < first) lo = mid + 1;
      else hi = mid;
    }
    const c = Math.max(0, lo - 1);
    this.coarse.geometry.setDrawRange(c, Math.max(0, this.coarseIndex.length - c));
  }
}
