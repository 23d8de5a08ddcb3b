/**
 * A job's whole path, shown the moment it is loaded: one line strip over all its
 * points, in the unplanned colour. As the job's moves are handed to the queue,
 * the strip's draw range starts later; the queue and the locked path draw the rest.
 */
import * as THREE from 'three';
import { Bounds } from './bounds.ts';

export class JobPreview {
  readonly line: THREE.Line;
  readonly bounds = new Bounds();
  private geometry = new THREE.BufferGeometry();
  private points = 0;

  constructor(color: string) {
    this.line = new THREE.Line(this.geometry, new THREE.LineBasicMaterial({ color, transparent: true, opacity: 0.8 }));
    this.line.frustumCulled = false;
  }

  /** (n + 1) × xyz vertices: the tool's start, then each move's end. */
  set(vertices: Float32Array): void {
    this.geometry.dispose();
    this.geometry = new THREE.BufferGeometry();
    this.geometry.setAttribute('position', new THREE.BufferAttribute(vertices, 3));
    this.line.geometry = this.geometry;
    this.points = vertices.length / 3;
    this.bounds.clear();
    this.bounds.addVertices(vertices);
    this.setFed(0);
  }

  clear(): void {
    this.points = 0;
    this.bounds.clear();
    this.geometry.setDrawRange(0, 0);
  }

  get segments(): number {
    return Math.max(0, this.points - 1);
  }

  /** Moves handed to the queue: the strip is drawn from the last of them on. */
  setFed(moves: number): void {
    const first = Math.min(moves, this.points);
    this.geometry.setDrawRange(first, Math.max(0, this.points - first));
  }
}
