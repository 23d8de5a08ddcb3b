/**
 * The untransmitted part of the trajectory (at most a queue's capacity of
 * segments): planned and unplanned, coloured per vertex. It changes as the
 * planner works, so it is rewritten whole, but it is small.
 */
import * as THREE from 'three';
import { QUEUE_PLANNED } from '../worker/protocol.ts';

export class QueueLines {
  readonly lines: THREE.LineSegments;
  private readonly geometry = new THREE.BufferGeometry();
  private readonly planned: THREE.Color;
  private readonly unplanned: THREE.Color;
  private capacity = 0;
  private position!: THREE.BufferAttribute;
  private color!: THREE.BufferAttribute;
  count = 0;

  constructor(plannedColor: string, unplannedColor: string) {
    this.planned = new THREE.Color(plannedColor);
    this.unplanned = new THREE.Color(unplannedColor);
    this.allocate(1024);
    this.lines = new THREE.LineSegments(this.geometry, new THREE.LineBasicMaterial({ vertexColors: true }));
    this.lines.frustumCulled = false;
    this.geometry.setDrawRange(0, 0);
  }

  set(vertices: Float32Array, states: Uint8Array): void {
    const n = states.length;
    if (n > this.capacity) {
      this.geometry.dispose();
      this.allocate(Math.max(n, this.capacity * 2));
    }
    (this.position.array as Float32Array).set(vertices);
    const colors = this.color.array as Float32Array;
    for (let i = 0; i < n; i++) {
      const c = states[i] === QUEUE_PLANNED ? this.planned : this.unplanned;
      for (let k = 0; k < 2; k++) {
        const o = (i * 2 + k) * 3;
        colors[o] = c.r;
        colors[o + 1] = c.g;
        colors[o + 2] = c.b;
      }
    }
    this.position.clearUpdateRanges();
    this.color.clearUpdateRanges();
    this.position.addUpdateRange(0, n * 6);
    this.color.addUpdateRange(0, n * 6);
    this.position.needsUpdate = true;
    this.color.needsUpdate = true;
    this.count = n;
    this.geometry.setDrawRange(0, n * 2);
  }

  clear(): void {
    this.count = 0;
    this.geometry.setDrawRange(0, 0);
  }

  private allocate(segments: number): void {
    this.capacity = segments;
    this.position = new THREE.BufferAttribute(new Float32Array(segments * 6), 3).setUsage(THREE.DynamicDrawUsage);
    this.color = new THREE.BufferAttribute(new Float32Array(segments * 6), 3).setUsage(THREE.DynamicDrawUsage);
    this.geometry.setAttribute('position', this.position);
    this.geometry.setAttribute('color', this.color);
  }
}
